#include "srp/interop/PoseConversions.h"

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose3D.h>
#include <visp3/core/vpHomogeneousMatrix.h>

namespace srp::interop {

using srp::core::Pose3;

vpHomogeneousMatrix toVisp(const Pose3& X) {
  vpHomogeneousMatrix M;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) M[r][c] = X.linear()(r, c);
    M[r][3] = X.translation()(r);
  }
  return M;
}

Pose3 fromVisp(const vpHomogeneousMatrix& M) {
  Pose3 X = Pose3::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) X.linear()(r, c) = M[r][c];
    X.translation()(r) = M[r][3];
  }
  return X;
}

mrpt::poses::CPose3D toMrpt(const Pose3& X) {
  mrpt::math::CMatrixDouble33 R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = X.linear()(r, c);
  mrpt::math::CVectorFixedDouble<3> t;
  for (int i = 0; i < 3; ++i) t[i] = X.translation()(i);
  return mrpt::poses::CPose3D(R, t);
}

Pose3 fromMrpt(const mrpt::poses::CPose3D& pose) {
  Pose3 X = Pose3::Identity();
  const auto R = pose.getRotationMatrix();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) X.linear()(r, c) = R(r, c);
  X.translation() = Eigen::Vector3d(pose.x(), pose.y(), pose.z());
  return X;
}

}  // namespace srp::interop
