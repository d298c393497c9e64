#pragma once
/// \file PoseConversions.h
/// \brief Exact conversions between srp::core::Pose3 and the pose types of
/// ViSP (vpHomogeneousMatrix, aMb convention) and MRPT (CPose3D). All three
/// mean the same thing: the pose of a child frame in a parent frame.
///
/// The ViSP and MRPT types are only declared here, so including this header
/// does not pull in those libraries; the caller includes the library header of
/// the type it uses.

#include "srp/core/Pose.h"

class vpHomogeneousMatrix;
namespace mrpt::poses {
class CPose3D;
}

namespace srp::core {

vpHomogeneousMatrix toVisp(const Pose3& X_A_B);
Pose3 fromVisp(const vpHomogeneousMatrix& aMb);

mrpt::poses::CPose3D toMrpt(const Pose3& X_A_B);
Pose3 fromMrpt(const mrpt::poses::CPose3D& pose);

}  // namespace srp::core
