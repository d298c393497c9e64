#pragma once
/// \file HandModel.h
/// \brief The synthetic demonstrator: an articulated right hand and forearm
/// with an AprilTag (tag36h11) on the back of the glove.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "srp/core/Pose.h"
#include "srp/kb/TriangleMesh.h"

namespace srp::synth {

/// One rigid piece of the hand (palm, finger segment, forearm, tag), its mesh
/// in the part's own frame with one colour (linear RGB) per triangle.
struct HandPart {
  std::string name;
  srp::kb::TriangleMesh mesh_part;
  std::vector<Eigen::Vector3d> triangleRgb;
  Eigen::AlignedBox3d bounds_part;  ///< for image masks
};

/// A right hand, palm down, built from boxes: palm, four two-segment fingers,
/// a two-segment thumb, wrist and sleeve, and the tag plate.
///
/// Hand frame (`hand`): origin at the palm centre, x towards the fingers, z out
/// of the back of the hand (up when the palm faces the table), y = z × x
/// (towards the thumb). Metres.
///
/// Tag frame (`tag`, as AprilTag and ViSP): origin at the tag centre, x right
/// and y down as the tag is read, z into the palm; `X_hand_tag()` places it on
/// the back of the hand. Its corners are returned top-left, top-right,
/// bottom-right, bottom-left in tag coordinates (±size/2).
///
/// `grip` in [0, 1] flexes the fingers from relaxed (0) to closed (1).
class HandModel {
 public:
  /// The hand's tag and colours.
  struct Options {
    int tagId = 0;               ///< tag36h11 id reserved for the demonstrator's hand
    double tagSize_m = 0.05;     ///< side of the tag's black square (AprilTag convention)
    Eigen::Vector3d skinRgb = Eigen::Vector3d(0.87, 0.64, 0.52);
    Eigen::Vector3d sleeveRgb = Eigen::Vector3d(0.22, 0.27, 0.42);
  };

  HandModel() : HandModel(Options{}) {}
  explicit HandModel(const Options& options);

  const std::vector<HandPart>& parts() const { return parts_; }
  /// X_hand_part of every part (same order as parts()) for a grip in [0, 1].
  std::vector<srp::core::Pose3> partPoses(double grip) const;

  srp::core::Pose3 X_hand_tag() const;
  std::array<Eigen::Vector3d, 4> tagCorners_tag() const;
  /// Half side of the tag plate (black square plus its one-cell white margin) [m].
  double tagPlateHalfSize_m() const { return 0.5 * options_.tagSize_m * static_cast<double>(tagCells_.size()) / (tagCells_.size() - 2.0); }
  const Options& options() const { return options_; }
  /// The tag's cells (including the white border) as read: row-major,
  /// true = black. 10 x 10 for tag36h11.
  const std::vector<std::vector<bool>>& tagCells() const { return tagCells_; }

  /// Height of the tag plate above the palm centre [m].
  static constexpr double kTagHeight_m = 0.0136;

 private:
  Options options_;
  std::vector<HandPart> parts_;
  std::vector<std::vector<bool>> tagCells_;
};

}  // namespace srp::synth
