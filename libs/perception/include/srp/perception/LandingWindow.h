#pragma once
/// \file LandingWindow.h
/// \brief Which pixels of a depth image can land in another camera's image when warped there.

#include <opencv2/core.hpp>

#include "srp/core/CameraIntrinsics.h"
#include "srp/core/Pose.h"

namespace srp::perception {

/// The pixels of a source depth image (camera `Ks`, its valid depths within [minDepth_m, maxDepth_m])
/// that can land in the image of camera `Kd` at pose X_dst_src (the source's points in the
/// destination's frame) when forward-warped: a point at source pixel (u, v) and depth z lands when
/// its projection, rounded, lies in the destination image and it is in front of that camera. Every
/// such pixel is inside the returned rectangle (clamped to the source image; a 2-px margin for
/// rounding). Bound: the destination's viewing frustum between the least and greatest depth a source
/// point can have in the destination camera (from the source image's corners and the depth range),
/// projected into the source by its 8 corners. The whole source image when that bound does not hold
/// (a corner behind the source camera, the cameras facing apart). Lets a warp skip the rest.
cv::Rect landingWindow(const core::CameraIntrinsics& Ks, float minDepth_m, float maxDepth_m,
                       const core::Pose3& X_dst_src, const core::CameraIntrinsics& Kd);

}  // namespace srp::perception
