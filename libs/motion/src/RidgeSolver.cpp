#include <Eigen/Eigenvalues>
#include <cmath>
#include <nlopt.hpp>

#include "ForcingBasis.h"
#include "LambdaSearch.h"

namespace srp::motion::detail {

RidgeSolver::RidgeSolver(const Eigen::MatrixXd& A, const Eigen::MatrixXd& F) {
  const Eigen::MatrixXd G = A.transpose() * A;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(G);
  s2_ = eig.eigenvalues();
  V_ = eig.eigenvectors();
  C_ = V_.transpose() * (A.transpose() * F);
  fNorm2_ = F.colwise().squaredNorm().transpose();
  n_ = static_cast<double>(A.rows());
  // Directions with eigenvalues below rounding level carry no information.
  s2Floor_ = 1e-14 * std::max(1e-300, s2_.cwiseAbs().maxCoeff());
}

double RidgeSolver::gcv(double lambda) const {
  double traceH = 0.0;
  double residual2 = 0.0;
  for (Eigen::Index d = 0; d < C_.cols(); ++d) residual2 += fNorm2_(d);
  for (Eigen::Index i = 0; i < s2_.size(); ++i) {
    if (s2_(i) <= s2Floor_) continue;
    const double h = s2_(i) / (s2_(i) + lambda);
    traceH += h;
    const double keep = 1.0 - (1.0 - h) * (1.0 - h);
    for (Eigen::Index d = 0; d < C_.cols(); ++d) residual2 -= keep * C_(i, d) * C_(i, d) / s2_(i);
  }
  residual2 = std::max(residual2, 0.0);
  const double dof = std::max(n_ - traceH, 1e-9);
  return n_ * residual2 / (dof * dof);
}

Eigen::MatrixXd RidgeSolver::weights(double lambda) const {
  Eigen::MatrixXd scaled = C_;
  for (Eigen::Index i = 0; i < s2_.size(); ++i) {
    const double denom = s2_(i) + lambda;
    scaled.row(i) = (s2_(i) <= s2Floor_ && lambda <= 0.0) ? Eigen::RowVectorXd::Zero(C_.cols()).eval()
                                                           : (scaled.row(i) / denom).eval();
  }
  return V_ * scaled;
}

LambdaChoice chooseLambdaByGcv(const RidgeSolver& solver, double lambdaMin, double lambdaMax) {
  // Coarse grid in log10(lambda), then NLopt's Subplex refines around the best
  // grid point (GCV can have several local minima; the grid avoids the wrong one).
  const double lo = std::log10(lambdaMin), hi = std::log10(lambdaMax);
  const int gridCount = 29;
  double bestX = lo, bestF = std::numeric_limits<double>::infinity();
  for (int i = 0; i < gridCount; ++i) {
    const double x = lo + (hi - lo) * i / (gridCount - 1);
    const double f = solver.gcv(std::pow(10.0, x));
    if (f < bestF) bestF = f, bestX = x;
  }
  const double cell = (hi - lo) / (gridCount - 1);
  nlopt::opt opt(nlopt::LN_SBPLX, 1);
  opt.set_lower_bounds(std::max(lo, bestX - cell));
  opt.set_upper_bounds(std::min(hi, bestX + cell));
  opt.set_xtol_abs(1e-3);
  opt.set_maxeval(60);
  auto objective = [](const std::vector<double>& x, std::vector<double>&, void* data) {
    return static_cast<const RidgeSolver*>(data)->gcv(std::pow(10.0, x[0]));
  };
  opt.set_min_objective(objective, const_cast<RidgeSolver*>(&solver));
  std::vector<double> x{bestX};
  double f = bestF;
  try {
    opt.optimize(x, f);
  } catch (const std::exception&) {
    // Roundoff stop: keep the best point NLopt or the grid found.
  }
  if (!(f <= bestF)) x[0] = bestX, f = bestF;
  return {std::pow(10.0, x[0]), f};
}

}  // namespace srp::motion::detail
