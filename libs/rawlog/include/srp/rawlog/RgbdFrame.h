#pragma once
/// \file RgbdFrame.h
/// \brief One RGB-D frame: colour and depth registered to the same pinhole
/// camera (depth pixel (u, v) sees the same ray as colour pixel (u, v)).

#include <opencv2/core.hpp>

#include "srp/core/CameraIntrinsics.h"

namespace srp::rawlog {

/// A registered RGB-D frame as srp's modules see it, whatever the source
/// (MRPT rawlog, image folder, renderer). Units: depth in metres, time in seconds.
struct RgbdFrame {
  int index = 0;                    ///< frame number in its recording, from 0
  double t_s = 0.0;                 ///< timestamp [s] (rawlogs: seconds since the epoch)
  cv::Mat colour_bgr8;              ///< CV_8UC3, BGR, height x width
  cv::Mat depth_m;                  ///< CV_32FC1, depth Z [m] along the optical axis, 0 = invalid
  srp::core::CameraIntrinsics intrinsics;  ///< of both images (registered)
  /// How depth came onto the colour grid: false when recorded so (the sensor
  /// registered it, or its two cameras coincide), true when srp re-projected
  /// the depth camera's image into the colour camera on reading
  /// (DepthRegistration; rawlog::needsRegistration says when).
  bool depthRegisteredOnRead = false;

  /// Throws InvalidInputError (naming `what`) when an image is missing, of the
  /// wrong type, or its size differs from the intrinsics'.
  void validate(const std::string& what) const;
};

}  // namespace srp::rawlog
