#pragma once
// Private: clamped cubic spline through demo samples, per column, giving
// positions, velocities and accelerations that are consistent with each other
// (finite differences of a coarse, fast demo are not, and a DMP integrating
// them drifts away from the demo by centimetres).

#include <Eigen/Core>

namespace srp::motion::detail {

using RowRef = Eigen::Ref<Eigen::RowVectorXd, 0, Eigen::InnerStride<>>;

class CubicSpline {
 public:
  /// t: N increasing times, Y: N x D; end slopes from second-order one-sided differences.
  CubicSpline(const Eigen::VectorXd& t, const Eigen::MatrixXd& Y);
  /// Position, velocity and acceleration at time tq (clamped to the demo interval).
  void evaluate(double tq, RowRef y, RowRef yd,
                RowRef ydd) const;

 private:
  Eigen::VectorXd t_;
  Eigen::MatrixXd Y_, M_;  // M_: second derivatives at the knots
};

}  // namespace srp::motion::detail
