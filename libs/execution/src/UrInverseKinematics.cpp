#include "srp/execution/UrInverseKinematics.h"

#include <cmath>

#include "srp/core/Error.h"
#include "srp/core/Pose.h"

namespace srp::execution {
namespace {

using srp::core::Pose3;

constexpr double kGeometryTol_m = 1e-6;

/// Standard DH link transform Rz(theta) Tz(d) Tx(a) Rx(alpha).
Eigen::Matrix4d dhLink(double theta, double d, double a, double alpha) {
  const double ct = std::cos(theta), st = std::sin(theta), ca = std::cos(alpha), sa = std::sin(alpha);
  Eigen::Matrix4d T;
  T << ct, -st * ca, st * sa, a * ct,  //
      st, ct * ca, -ct * sa, a * st,   //
      0, sa, ca, d,                    //
      0, 0, 0, 1;
  return T;
}

struct Dh {
  std::array<double, 6> d, a, alpha;
};

Dh dhTable(const UrDhParameters& p) {
  return {{p.d1_m, 0.0, 0.0, p.d4_m, p.d5_m, p.d6_m},
          {0.0, p.a2_m, p.a3_m, 0.0, 0.0, 0.0},
          {M_PI / 2, 0.0, 0.0, M_PI / 2, -M_PI / 2, 0.0}};
}

}  // namespace

UrInverseKinematics::UrInverseKinematics(const RobotModel& model) : model_(model) {
  const auto& j = model.joints();
  const auto t = [&](int i) { return j[i].X_parent_joint.translation(); };
  dh_.d1_m = t(0).z();
  dh_.a2_m = t(2).x();
  dh_.a3_m = t(3).x();
  dh_.d4_m = t(3).z();
  dh_.d5_m = -t(4).y();
  dh_.d6_m = t(5).y();
  const bool urGeometry = t(0).head<2>().norm() < kGeometryTol_m && t(1).norm() < kGeometryTol_m &&
                          std::abs(t(2).y()) + std::abs(t(2).z()) < kGeometryTol_m &&
                          std::abs(t(3).y()) < kGeometryTol_m &&
                          std::abs(t(4).x()) + std::abs(t(4).z()) < kGeometryTol_m &&
                          std::abs(t(5).x()) + std::abs(t(5).z()) < kGeometryTol_m;
  if (!urGeometry)
    throw srp::core::InvalidInputError(
        "UrInverseKinematics: robot '" + model.name() +
        "' does not have UR joint geometry (offsets d1, a2, a3, d4, d5, d6 only); use a UR URDF");
  // The DH base coincides with base_link for UR descriptions; the tool0 offset is measured.
  X_base_dh0_ = Pose3::Identity();
  // forwardTool0 still uses the identity offset here, so this measures DH frame 6 -> tool0.
  X_dh6_tool0_ = forwardTool0(JointVector::Zero()).inverse() * model.X_base_tool0(JointVector::Zero());
}

srp::core::Pose3 UrInverseKinematics::forwardTool0(const JointVector& q) const {
  const Dh t = dhTable(dh_);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (int i = 0; i < 6; ++i) T = T * dhLink(q[i], t.d[i], t.a[i], t.alpha[i]);
  Pose3 X;
  X.matrix() = T;
  return X_base_dh0_ * X * X_dh6_tool0_;
}

std::vector<JointVector> UrInverseKinematics::solveAll(const srp::core::Pose3& X_base_tool0,
                                                       double q6Hint_rad) const {
  const Dh t = dhTable(dh_);
  const Eigen::Matrix4d T06 = (X_base_dh0_.inverse() * X_base_tool0 * X_dh6_tool0_.inverse()).matrix();
  const double d4 = dh_.d4_m, d6 = dh_.d6_m, a2 = dh_.a2_m, a3 = dh_.a3_m;
  std::vector<JointVector> out;

  const Eigen::Vector4d p05 = T06 * Eigen::Vector4d(0, 0, -d6, 1);
  const double r05 = std::hypot(p05.x(), p05.y());
  if (r05 < std::abs(d4)) return out;  // wrist centre inside the shoulder cylinder
  const double phi1 = std::atan2(p05.y(), p05.x());
  const double phi2 = std::acos(d4 / r05);
  const Eigen::Matrix4d T60 = T06.inverse();
  for (int s1 : {1, -1}) {
    const double q1 = phi1 + s1 * phi2 + M_PI / 2;
    const double c1 = std::cos(q1), s1v = std::sin(q1);
    double arg5 = (T06(0, 3) * s1v - T06(1, 3) * c1 - d4) / d6;
    if (std::abs(arg5) > 1.0 + 1e-12) continue;
    arg5 = std::clamp(arg5, -1.0, 1.0);
    for (int s5 : {1, -1}) {
      const double q5 = s5 * std::acos(arg5);
      const double sin5 = std::sin(q5);
      double q6 = q6Hint_rad;
      if (std::abs(sin5) > 1e-9)
        q6 = std::atan2((-T60(1, 0) * s1v + T60(1, 1) * c1) / sin5,
                        (T60(0, 0) * s1v - T60(0, 1) * c1) / sin5);
      const Eigen::Matrix4d T01 = dhLink(q1, t.d[0], t.a[0], t.alpha[0]);
      const Eigen::Matrix4d T45 = dhLink(q5, t.d[4], t.a[4], t.alpha[4]);
      const Eigen::Matrix4d T56 = dhLink(q6, t.d[5], t.a[5], t.alpha[5]);
      const Eigen::Matrix4d T14 = T01.inverse() * T06 * (T45 * T56).inverse();
      const Eigen::Vector4d p13h = T14 * Eigen::Vector4d(0, -d4, 0, 1);
      const Eigen::Vector3d p13 = p13h.head<3>();
      const double n13 = p13.norm();
      double arg3 = (n13 * n13 - a2 * a2 - a3 * a3) / (2.0 * a2 * a3);
      if (std::abs(arg3) > 1.0 + 1e-12) continue;
      arg3 = std::clamp(arg3, -1.0, 1.0);
      for (int s3 : {1, -1}) {
        const double q3 = s3 * std::acos(arg3);
        const double q2 = -std::atan2(p13.y(), -p13.x()) + std::asin(std::clamp(a3 * std::sin(q3) / n13, -1.0, 1.0));
        const Eigen::Matrix4d T12 = dhLink(q2, t.d[1], t.a[1], t.alpha[1]);
        const Eigen::Matrix4d T23 = dhLink(q3, t.d[2], t.a[2], t.alpha[2]);
        const Eigen::Matrix4d T34 = T23.inverse() * T12.inverse() * T14;
        const double q4 = std::atan2(T34(1, 0), T34(0, 0));
        JointVector q;
        q << q1, q2, q3, q4, q5, q6;
        for (int i = 0; i < 6; ++i) q[i] = core::angleDifference(q[i], 0.0);  // to (-pi, pi]
        out.push_back(q);
      }
    }
  }
  return out;
}

std::optional<JointVector> UrInverseKinematics::solveNearest(const srp::core::Pose3& X_base_tool0,
                                                             const JointVector& q_current) const {
  std::optional<JointVector> best;
  double bestDistance = 0.0;
  for (JointVector q : solveAll(X_base_tool0, q_current[5])) {
    bool ok = true;
    for (int i = 0; i < 6 && ok; ++i) {
      // Shift by 2 pi k towards the current joint, then back inside the limits.
      q[i] = q_current[i] + core::angleDifference(q[i], q_current[i]);
      const auto& jl = model_.joints()[i];
      while (q[i] > jl.upper_rad) q[i] -= 2.0 * M_PI;
      while (q[i] < jl.lower_rad) q[i] += 2.0 * M_PI;
      ok = q[i] <= jl.upper_rad;
    }
    if (!ok) continue;
    const double distance = (q - q_current).norm();
    if (!best || distance < bestDistance) {
      best = q;
      bestDistance = distance;
    }
  }
  return best;
}

std::optional<JointVector> UrInverseKinematics::solveNearestTcp(const srp::core::Pose3& X_base_tcp,
                                                                const JointVector& q_current) const {
  return solveNearest(X_base_tcp * model_.X_tool0_tcp().inverse(), q_current);
}

}  // namespace srp::execution
