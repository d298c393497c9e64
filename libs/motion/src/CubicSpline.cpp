#include "CubicSpline.h"

#include <algorithm>

namespace srp::motion::detail {

CubicSpline::CubicSpline(const Eigen::VectorXd& t, const Eigen::MatrixXd& Y) : t_(t), Y_(Y) {
  const Eigen::Index n = t.size(), D = Y.cols();
  M_.setZero(n, D);
  // End slopes: second-order one-sided differences (first-order with 2 samples).
  Eigen::RowVectorXd s0, s1;
  if (n >= 3) {
    const double h0 = t(1) - t(0), h1 = t(2) - t(1);
    s0 = -(2 * h0 + h1) / (h0 * (h0 + h1)) * Y.row(0) + (h0 + h1) / (h0 * h1) * Y.row(1) -
         h0 / (h1 * (h0 + h1)) * Y.row(2);
    const double a = t(n - 2) - t(n - 3), b = t(n - 1) - t(n - 2);
    s1 = b / (a * (a + b)) * Y.row(n - 3) - (a + b) / (a * b) * Y.row(n - 2) +
         (2 * b + a) / (b * (a + b)) * Y.row(n - 1);
  } else {
    s0 = s1 = (Y.row(1) - Y.row(0)) / (t(1) - t(0));
  }
  // Tridiagonal system for the knot second derivatives (clamped ends), Thomas algorithm.
  Eigen::VectorXd lower(n), diag(n), upper(n);
  Eigen::MatrixXd rhs(n, D);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (i == 0) {
      const double h = t(1) - t(0);
      lower(i) = 0, diag(i) = h / 3, upper(i) = h / 6;
      rhs.row(i) = (Y.row(1) - Y.row(0)) / h - s0;
    } else if (i == n - 1) {
      const double h = t(i) - t(i - 1);
      lower(i) = h / 6, diag(i) = h / 3, upper(i) = 0;
      rhs.row(i) = s1 - (Y.row(i) - Y.row(i - 1)) / h;
    } else {
      const double hl = t(i) - t(i - 1), hr = t(i + 1) - t(i);
      lower(i) = hl / 6, diag(i) = (hl + hr) / 3, upper(i) = hr / 6;
      rhs.row(i) = (Y.row(i + 1) - Y.row(i)) / hr - (Y.row(i) - Y.row(i - 1)) / hl;
    }
  }
  for (Eigen::Index i = 1; i < n; ++i) {
    const double m = lower(i) / diag(i - 1);
    diag(i) -= m * upper(i - 1);
    rhs.row(i) -= m * rhs.row(i - 1);
  }
  M_.row(n - 1) = rhs.row(n - 1) / diag(n - 1);
  for (Eigen::Index i = n - 2; i >= 0; --i) M_.row(i) = (rhs.row(i) - upper(i) * M_.row(i + 1)) / diag(i);
}

void CubicSpline::evaluate(double tq, RowRef y, RowRef yd,
                           RowRef ydd) const {
  const Eigen::Index n = t_.size();
  tq = std::clamp(tq, t_(0), t_(n - 1));
  const auto it = std::upper_bound(t_.data(), t_.data() + n, tq);
  const Eigen::Index i = std::clamp<Eigen::Index>((it - t_.data()) - 1, 0, n - 2);
  const double h = t_(i + 1) - t_(i), a = (t_(i + 1) - tq) / h, b = (tq - t_(i)) / h;
  y = a * Y_.row(i) + b * Y_.row(i + 1) + ((a * a * a - a) * M_.row(i) + (b * b * b - b) * M_.row(i + 1)) * h * h / 6;
  yd = (Y_.row(i + 1) - Y_.row(i)) / h - (3 * a * a - 1) / 6 * h * M_.row(i) + (3 * b * b - 1) / 6 * h * M_.row(i + 1);
  ydd = a * M_.row(i) + b * M_.row(i + 1);
}

}  // namespace srp::motion::detail
