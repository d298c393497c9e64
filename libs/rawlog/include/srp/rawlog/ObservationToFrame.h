#pragma once
/// \file ObservationToFrame.h
/// \brief Conversion of one MRPT RGB-D observation to an srp RgbdFrame, shared
/// by RawlogReader and live grabbers (srp record). The MRPT type is only
/// declared here; callers that have one include its MRPT header themselves.

#include <string>

#include "srp/core/Pose.h"
#include "srp/rawlog/DepthRegistration.h"
#include "srp/rawlog/RgbdFrame.h"

namespace mrpt::obs {
class CObservation3DRangeScan;
}

namespace srp::rawlog {

/// The two cameras an MRPT observation describes, in srp's conventions.
struct ObservationCameras {
  DepthRegistration::Camera depth;   ///< cameraParams (rangeImage's size)
  DepthRegistration::Camera colour;  ///< cameraParamsIntensity (intensityImage's size)
  /// From relativePoseIntensityWRTDepth, which MRPT gives in the depth
  /// sensor's x-forward frame; both optical frames here are x right, y down, z forward.
  srp::core::Pose3 X_colour_depth = srp::core::Pose3::Identity();
  bool sameSize = true;         ///< range and intensity images have the same size
  bool mrptCoincide = true;     ///< MRPT's doDepthAndIntensityCamerasCoincide() (pose equal within 1e-7)
  double baseline_m = 0.0;      ///< distance between the two optical centres
  double rotation_rad = 0.0;    ///< angle between the two optical frames
};

/// Reads the cameras of `obs` (sizes from the images when MRPT's ncols/nrows are unset).
ObservationCameras observationCameras(const mrpt::obs::CObservation3DRangeScan& obs);

/// What frameFromObservation does with the depth image.
enum class DepthRegistrationMode {
  Auto,        ///< register exactly when needsRegistration() says so
  AsRecorded,  ///< never (depth pixel (u, v) taken as colour pixel (u, v); sizes must agree)
  Register,    ///< always (DepthRegistration from the observation's two cameras)
};

/// The reader's decision (DepthRegistrationMode::Auto): depth is re-projected
/// into the colour camera when the two images differ in size, or when the
/// colour camera's optical centre is more than kCoincideBaseline_m from the
/// depth camera's or its axes are turned by more than kCoincideRotation_rad.
/// Otherwise depth pixel (u, v) is colour pixel (u, v), as MRPT itself pairs
/// them when doDepthAndIntensityCamerasCoincide() (it then ignores
/// cameraParamsIntensity too). `reason` (optional) receives one line saying why.
bool needsRegistration(const ObservationCameras& cameras, std::string* reason = nullptr);
constexpr double kCoincideBaseline_m = 2e-3;
constexpr double kCoincideRotation_rad = 1e-3;

/// Depth = rangeImage x rangeUnits [m] (range converted to depth along the
/// axis when range_is_depth is false); colour = the intensity image (grey
/// converted to BGR; empty when there is none). Registered observations
/// (see needsRegistration) keep the depth camera's intrinsics and, when the
/// colour image alone has another size, the colour is resized onto the depth
/// grid (as before). Otherwise depth is registered to colour (DepthRegistration)
/// and the frame carries the colour camera's intrinsics with
/// depthRegisteredOnRead set; the colour image is never resized then. The
/// observation must be loaded (obs.load()) and have a range image.
RgbdFrame frameFromObservation(const mrpt::obs::CObservation3DRangeScan& obs, int index,
                               DepthRegistrationMode mode = DepthRegistrationMode::Auto);

}  // namespace srp::rawlog
