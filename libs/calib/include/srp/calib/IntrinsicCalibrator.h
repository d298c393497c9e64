#pragma once
/// \file IntrinsicCalibrator.h
/// \brief Intrinsic camera calibration from images of a planar pattern
/// (OpenCV's calibrateCamera restricted to ViSP's distortion model, so the
/// result is exactly what a ViSP camera XML file stores).

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "srp/calib/CalibrationPattern.h"
#include "srp/calib/CameraCalibration.h"
#include "srp/calib/ImageHeader.h"
#include "srp/core/Pose.h"

namespace srp::calib {

/// A view whose reprojection RMS is this many times the median view's is flagged
/// CalibrationView::outlier.
constexpr double kOutlierViewFactor = 3.0;

/// One calibration image: where it came from and what was found in it.
struct CalibrationView {
  std::string name;                  ///< file path (or a label for in-memory images)
  bool found = false;                ///< pattern detected (else rejected)
  int points = 0;                    ///< points used
  double rms_px = 0.0;               ///< reprojection RMS of this view with the final camera
  /// rms_px is at least kOutlierViewFactor times the median of the used views'
  /// rms_px: a blurred image, a bent board or a wrong detection, to check or drop.
  /// Flagged only; the view stays in the calibration.
  bool outlier = false;
  srp::core::Pose3 X_camera_board = srp::core::Pose3::Identity();  ///< estimated board pose
  PatternObservation observation;
};

/// The calibrated camera and how well it explains the images.
struct IntrinsicCalibrationResult {
  CameraCalibration camera;
  double rms_px = 0.0;               ///< reprojection RMS over all points of the used views
  std::vector<CalibrationView> views;  ///< in input order, rejected ones with found = false
  double medianViewRms_px = 0.0;     ///< median of the used views' rms_px
  int viewsUsed() const;
  std::vector<std::string> rejectedNames() const;
  std::vector<std::string> outlierNames() const;  ///< views flagged CalibrationView::outlier, in input order
};

struct IntrinsicCalibrationOptions {
  bool estimateDistortion = true;    ///< false: kud = kdu = 0
  std::string cameraName = "Camera";
  std::string drawDir;               ///< when set, one PNG per image with the detection
  /// Images whose header declares more pixels are refused before decoding (ImageHeader.h).
  std::int64_t maxImagePixels = kMaxImagePixels;
  /// Progress callback (image index, count, name), e.g. to print to stderr.
  std::function<void(int, int, const std::string&)> progress;
};

/// Calibrates from in-memory images (8-bit grey or BGR, all the same size;
/// names label them in results and errors). Throws InvalidInputError when the
/// sizes differ or fewer than 3 views show the pattern (naming the rejected ones).
IntrinsicCalibrationResult calibrateIntrinsics(const std::vector<cv::Mat>& images,
                                               const std::vector<std::string>& names,
                                               const CalibrationPattern& pattern,
                                               const IntrinsicCalibrationOptions& options = {});

/// Reads the image files and calibrates; throws FileError naming an unreadable file.
IntrinsicCalibrationResult calibrateIntrinsicsFromFiles(const std::vector<std::string>& imagePaths,
                                                        const CalibrationPattern& pattern,
                                                        const IntrinsicCalibrationOptions& options = {});

/// Expands a shell-style file pattern (`calib/*.png`; `*`, `?` and `[...]` in
/// the file name only) to the sorted list of matching files; a plain path is returned
/// as is. Throws FileError naming the pattern when nothing matches.
std::vector<std::string> expandImageGlob(const std::string& pattern);

}  // namespace srp::calib
