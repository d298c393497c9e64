#pragma once
// Private: the Gaussian basis of the forcing term in phase space, laid out as
// dfki-ric movement_primitives' ForcingTerm does (centres equally spaced in
// time, widths so that a basis has value `overlap` at its neighbour's centre).

#include <Eigen/Core>
#include <cmath>

namespace srp::motion::detail {

class ForcingBasis {
 public:
  ForcingBasis() = default;
  ForcingBasis(int count, double alpha_z, double overlap) : alpha_z_(alpha_z) {
    centers_.resize(count);
    widths_.resize(count);
    const double logOverlap = -std::log(overlap);
    const double step = 1.0 / (count - 1);  // normalised duration 1
    centers_(0) = phase(0.0);
    for (int i = 1; i < count; ++i) {
      centers_(i) = phase(i * step);
      const double diff = centers_(i) - centers_(i - 1);
      widths_(i - 1) = logOverlap / (diff * diff);
    }
    widths_(count - 1) = widths_(count - 2);
  }

  /// Phase z at normalised time s = (t - t0) / tau.
  double phase(double s) const { return std::exp(-alpha_z_ * s); }

  /// Normalised activations times z: column of the design matrix (N).
  template <typename Out>
  void activations(double z, Out&& out) const {
    const int n = static_cast<int>(centers_.size());
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
      const double d = z - centers_(i);
      out(i) = std::exp(-widths_(i) * d * d);
      sum += out(i);
    }
    for (int i = 0; i < n; ++i) out(i) = out(i) / sum * z;
  }

  Eigen::VectorXd activations(double z) const {
    Eigen::VectorXd a(centers_.size());
    activations(z, a);
    return a;
  }

  const Eigen::VectorXd& centers() const { return centers_; }
  const Eigen::VectorXd& widths() const { return widths_; }
  int size() const { return static_cast<int>(centers_.size()); }

 private:
  double alpha_z_ = 0.0;
  Eigen::VectorXd centers_, widths_;
};

/// numpy.gradient with unit spacing and edge_order 1, per column.
inline Eigen::MatrixXd numpyGradient(const Eigen::MatrixXd& f) {
  const Eigen::Index n = f.rows();
  Eigen::MatrixXd g(n, f.cols());
  g.row(0) = f.row(1) - f.row(0);
  g.row(n - 1) = f.row(n - 1) - f.row(n - 2);
  for (Eigen::Index i = 1; i + 1 < n; ++i) g.row(i) = (f.row(i + 1) - f.row(i - 1)) / 2.0;
  return g;
}

/// Ridge regression solved by eigen-decomposition of the Gram matrix A^T A
/// (A = N x K design), giving weights and the GCV error for any lambda cheaply.
class RidgeSolver {
 public:
  RidgeSolver(const Eigen::MatrixXd& A, const Eigen::MatrixXd& F);  // F: N x D targets
  /// GCV(lambda) = sum_d N ||(I - H) f_d||^2 / (N - tr H)^2.
  double gcv(double lambda) const;
  /// K x D weights for lambda.
  Eigen::MatrixXd weights(double lambda) const;

 private:
  Eigen::VectorXd s2_;  // eigenvalues of A^T A (squared singular values)
  Eigen::MatrixXd V_;   // eigenvectors
  Eigen::MatrixXd C_;   // V^T A^T F (K x D)
  Eigen::VectorXd fNorm2_;
  double n_ = 0.0;
  double s2Floor_ = 0.0;
};

}  // namespace srp::motion::detail
