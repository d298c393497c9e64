#pragma once
/// \file PerceptionDrawing.h
/// \brief What perception saw, drawn on the recording: per frame the palm,
/// every part and container (the outline of its model at its pose, its name and
/// the detection's confidence) and the table frame; and a contact sheet of such
/// frames with captions (`srp program --report`, `srp perceive --draw`).
///
/// \code
///   const srp::perception::PerceptionResult seen = perceiveRawlog(path, kb, options);  // RawlogPerception.h
///   const srp::perception::PerceptionDrawing drawing(seen, kb);
///   srp::rawlog::RawlogReader reader(path);
///   while (auto f = reader.next()) {
///     cv::Mat image = f->colour_bgr8.clone();
///     drawing.draw(image, f->index);   // palm, outlines, names, confidences, table axes
///   }
/// \endcode

#include <opencv2/core.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "srp/core/ObjectCatalogue.h"
#include "srp/perception/DemoPerception.h"

namespace srp::perception {

/// Draws one frame of a PerceptionResult onto that frame's colour image
/// (intrinsics of the result). Drawn, in the image of frame `frame`:
/// - each object's outline: the convex hull of its class mesh's vertices
///   projected at the object's pose, in the class' colour, solid when detected in
///   this frame, thin and grey when the pose is carried from another frame; its
///   key (instance id or class) and confidence ("toy 0.82", "(kept)");
/// - the palm: a white disc with a black ring where the hand was detected, the
///   word "no hand" in the corner where it was not;
/// - the table frame: x (red), y (green) and z (blue) axes of `axisLength_m`
///   at its origin, and the table rectangle when a size is given.
class PerceptionDrawing {
 public:
  struct Options {
    /// The table frame to draw; nullopt = the result's support plane
    /// (PerceptionResult::X_camera_table), none when it has none.
    std::optional<core::Pose3> X_camera_table;
    std::optional<Eigen::Vector2d> tableSize_m;  ///< the table rectangle around the frame's origin
    double axisLength_m = 0.1;
    /// Text and line size for an image this wide (labels stay readable when the
    /// image is shrunk to this width, as on a contact sheet).
    int readableWidth_px = 480;
  };

  /// Builds the outlines of every class the result holds (kb::loadClassMesh).
  /// Throws what loading a class' mesh throws (FileError naming the file).
  PerceptionDrawing(const PerceptionResult& result, const core::ObjectCatalogue& catalogue);
  PerceptionDrawing(const PerceptionResult& result, const core::ObjectCatalogue& catalogue, Options options);

  /// Draws frame `frame` (the rawlog's frame index) on `bgr8` (CV_8UC3 of the
  /// result's image size; another size is scaled to).
  void draw(cv::Mat& bgr8, int frame) const;

 private:
  PerceptionResult result_;
  Options options_;
  std::map<std::string, std::vector<Eigen::Vector3d>> hull_object_;  ///< per class: mesh vertices, object frame
  std::map<std::string, cv::Scalar> colour_;                          ///< per class, BGR
};

/// One tile of a contact sheet: a drawn frame and its caption.
struct ContactSheetTile {
  cv::Mat image;             ///< BGR8, any size (scaled to the tile width)
  std::string caption;       ///< "frame 42  GRASP toy"
  cv::Scalar border = cv::Scalar(60, 60, 60);  ///< BGR of the tile's frame
  std::string flag;          ///< printed in red across the top when set ("LOW CONFIDENCE")
};

/// The tiles in rows of `columns`, each `tileWidth_px` wide (height by the
/// first tile's aspect), a caption under each, a title line on top. BGR8.
cv::Mat composeContactSheet(const std::vector<ContactSheetTile>& tiles, const std::string& title, int columns = 4,
                            int tileWidth_px = 480);

/// Frames to show on a contact sheet of a recording of `frameCount` frames:
/// `count` evenly spread (first and last included) plus every frame of
/// `marked`, sorted, without repeats.
std::vector<int> contactSheetFrames(int frameCount, int count, const std::vector<int>& marked = {});

/// What `srp perceive --draw DIR` writes: the recording at `rawlogPath` read
/// again, every `every`-th frame drawn (PerceptionDrawing) as `frame_NNNNN.png`,
/// and `contact_sheet.png` of `sheetFrames` frames spread over the recording.
/// The folder is built aside and renamed into place (core::AtomicOutputFolder):
/// a failure leaves no half-written folder; an existing one is replaced.
/// Returns the files written. Throws FileError naming the folder or the rawlog.
std::vector<std::string> writeDrawnFrames(const std::string& rawlogPath, const PerceptionResult& result,
                                          const core::ObjectCatalogue& catalogue, const std::string& folder,
                                          int every = 1, int sheetFrames = 12);

}  // namespace srp::perception
