#pragma once
/// \file PoseConversions.h
/// \brief Exact conversions between srp::core::Pose3 and the pose types of
/// ViSP (vpHomogeneousMatrix, aMb convention) and MRPT (CPose3D). All three
/// mean the same thing: the pose of a child frame in a parent frame.
///
/// srp::interop is the one library that links ViSP and MRPT for srp::core's
/// types, so that core itself links Eigen and nlohmann-json only; the modules
/// that speak ViSP or MRPT (perception, synth, calib, execution) link it
/// privately.
///
/// The ViSP and MRPT types are only declared here, so including this header
/// does not pull in those libraries; the caller includes the library header of
/// the type it uses.

#include "srp/core/Pose.h"

class vpHomogeneousMatrix;
namespace mrpt::poses {
class CPose3D;
}

namespace srp::interop {

vpHomogeneousMatrix toVisp(const srp::core::Pose3& X_A_B);
srp::core::Pose3 fromVisp(const vpHomogeneousMatrix& aMb);

mrpt::poses::CPose3D toMrpt(const srp::core::Pose3& X_A_B);
srp::core::Pose3 fromMrpt(const mrpt::poses::CPose3D& pose);

}  // namespace srp::interop
