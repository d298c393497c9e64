#include "srp/motion/Dmp.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <cmath>

#include "CubicSpline.h"
#include "ForcingBasis.h"
#include "JsonEigen.h"
#include "LambdaSearch.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"

namespace srp::motion {
namespace {

using core::InvalidInputError;
using core::require;

/// numpy.linalg.pinv (SVD, cut-off 1e-15 of the largest singular value).
Eigen::MatrixXd numpyPinv(const Eigen::MatrixXd& M) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  const double cutoff = 1e-15 * s.maxCoeff();
  Eigen::VectorXd sInv = s;
  for (Eigen::Index i = 0; i < s.size(); ++i) sInv(i) = s(i) > cutoff ? 1.0 / s(i) : 0.0;
  return svd.matrixV() * sInv.asDiagonal() * svd.matrixU().transpose();
}

void validateDemo(const Eigen::VectorXd& t_s, const Eigen::MatrixXd& Y) {
  require(t_s.size() == Y.rows(), "DMP demo: " + std::to_string(t_s.size()) + " times but " +
                                      std::to_string(Y.rows()) + " samples; give one time per sample");
  require(Y.rows() >= 3, "DMP demo has " + std::to_string(Y.rows()) +
                             " samples; a DMP needs at least 3 (an empty or single-sample segment "
                             "cannot be learned)");
  require(Y.cols() >= 1, "DMP demo has no dimensions");
  require(t_s.allFinite() && Y.allFinite(),
          "DMP demo has a NaN or infinite sample; fill or drop missing samples first");
  for (Eigen::Index i = 1; i < t_s.size(); ++i)
    require(t_s(i) > t_s(i - 1), "DMP demo times must increase strictly (sample " +
                                     std::to_string(i) + ")");
}

struct DefaultIntegration {
  const detail::ForcingBasis& basis;
  const Eigen::MatrixXd& SW;  // scaled weights, D x N
  const Eigen::VectorXd &goal, &goalVel_s, &start, &startVel_s;
  double a, b, tau, maxStep_s;
};

/// Classical RK4 in s with the forcing term at the stage times; Dim = 3 keeps
/// every vector on the stack (a rollout then allocates nothing but its output).
template <int Dim>
void integrateDefault(const DefaultIntegration& in, DmpRollout& out) {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  const Eigen::Index D = in.SW.rows(), n = out.t_s.size();
  Eigen::VectorXd act(in.SW.cols());
  auto forcing = [&](double s, Vec& f) {
    in.basis.activations(in.basis.phase(s), act);
    f.noalias() = in.SW * act;
  };
  const Vec goal = in.goal, goalVel = in.goalVel_s;
  Vec y = in.start, v = in.startVel_s, fA(D), fM(D), fB(D);
  auto acc = [&](const Vec& Y, const Vec& V, const Vec& f) -> Vec { return in.a * (in.b * (goal - Y) + (goalVel - V)) + f; };
  out.y.row(0) = y.transpose();
  out.yd.row(0) = (v / in.tau).transpose();
  forcing(0.0, fA);
  for (Eigen::Index i = 1; i < n; ++i) {
    const double s0 = out.t_s(i - 1) / in.tau, s1 = out.t_s(i) / in.tau;
    const int m = std::max(1, static_cast<int>(std::ceil((s1 - s0) / in.maxStep_s - 1e-12)));
    const double h = (s1 - s0) / m;
    for (int k = 0; k < m; ++k) {
      const double s = s0 + k * h;
      forcing(s + 0.5 * h, fM);
      forcing(s + h, fB);
      const Vec k1v = acc(y, v, fA), k1y = v;
      const Vec k2y = v + 0.5 * h * k1v, k2v = acc(y + 0.5 * h * k1y, k2y, fM);
      const Vec k3y = v + 0.5 * h * k2v, k3v = acc(y + 0.5 * h * k2y, k3y, fM);
      const Vec k4y = v + h * k3v, k4v = acc(y + h * k3y, k4y, fB);
      y += h / 6.0 * (k1y + 2 * k2y + 2 * k3y + k4y);
      v += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v);
      fA = fB;
    }
    out.y.row(i) = y.transpose();
    out.yd.row(i) = (v / in.tau).transpose();
  }
}


// The "demo" and "configured" blocks of the JSON: start, goal, normalised
// start/goal velocities and duration (the demo block adds its sample period).
nlohmann::json endpointsJson(const Eigen::VectorXd& start, const Eigen::VectorXd& goal, const Eigen::VectorXd& startVel_s,
                             const Eigen::VectorXd& goalVel_s, double duration_s) {
  using detail::toJson;
  return {{"start", toJson(start)},
          {"goal", toJson(goal)},
          {"start_velocity_normalised", toJson(startVel_s)},
          {"goal_velocity_normalised", toJson(goalVel_s)},
          {"duration_s", duration_s}};
}

void endpointsFromJson(const nlohmann::json& block, Eigen::Index D, const std::string& ctx, Eigen::VectorXd& start,
                       Eigen::VectorXd& goal, Eigen::VectorXd& startVel_s, Eigen::VectorXd& goalVel_s, double& duration_s) {
  using core::requireField;
  using detail::vectorFromJson;
  start = vectorFromJson(requireField(block, "start", ctx), D, ctx + ".start");
  goal = vectorFromJson(requireField(block, "goal", ctx), D, ctx + ".goal");
  startVel_s = vectorFromJson(requireField(block, "start_velocity_normalised", ctx), D, ctx + ".start_velocity_normalised");
  goalVel_s = vectorFromJson(requireField(block, "goal_velocity_normalised", ctx), D, ctx + ".goal_velocity_normalised");
  duration_s = requireField(block, "duration_s", ctx).get<double>();
}

}  // namespace

void Dmp::Options::validate() const {
  using core::require;
  require(basisCount >= 2, "Dmp::Options.basisCount must be >= 2 (got " + std::to_string(basisCount) + ")");
  require(alpha_y > 0 && beta_y > 0 && std::isfinite(alpha_y) && std::isfinite(beta_y),
          "Dmp::Options.alpha_y and beta_y must be positive and finite");
  require(alpha_z > 0 && std::isfinite(alpha_z), "Dmp::Options.alpha_z must be positive");
  require(overlap > 0 && overlap < 1, "Dmp::Options.overlap must be in (0, 1)");
  if (lambda)
    require(*lambda >= 0 && std::isfinite(*lambda), "Dmp::Options.lambda must be >= 0 and finite");
  require(mode == Mode::Default || lambda.has_value(),
          "Dmp::Options: Reference mode needs a lambda (the thesis used 0.1)");
  require(mode == Mode::Default || scaling == ForcingScaling::None,
          "Dmp::Options: Reference mode has no forcing scaling; use Mode::Default for scaling");
  require(lambdaSearchMin > 0 && lambdaSearchMax > lambdaSearchMin,
          "Dmp::Options: need 0 < lambdaSearchMin < lambdaSearchMax");
  require(referenceDt_s > 0, "Dmp::Options.referenceDt_s must be positive");
  require(maxStepFraction > 0 && maxStepFraction <= 1, "Dmp::Options.maxStepFraction must be in (0, 1]");
}

std::string toString(ForcingScaling s) {
  switch (s) {
    case ForcingScaling::None: return "none";
    case ForcingScaling::PerDimension: return "per_dimension";
    case ForcingScaling::Spatial: return "spatial";
  }
  return "none";
}

ForcingScaling forcingScalingFromString(const std::string& text) {
  if (text == "none") return ForcingScaling::None;
  if (text == "per_dimension") return ForcingScaling::PerDimension;
  if (text == "spatial") return ForcingScaling::Spatial;
  throw core::InvalidInputError("unknown forcing scaling '" + text +
                                "'; use none, per_dimension or spatial");
}

void to_json(nlohmann::json& j, const Dmp::Options& c) {
  j = nlohmann::json{{"mode", c.mode == Dmp::Options::Mode::Reference ? "reference" : "default"},
                     {"basis_count", c.basisCount},
                     {"alpha_y", c.alpha_y},
                     {"beta_y", c.beta_y},
                     {"alpha_z", c.alpha_z},
                     {"overlap", c.overlap},
                     {"scaling", toString(c.scaling)},
                     {"lambda", c.lambda ? nlohmann::json(*c.lambda) : nlohmann::json(nullptr)},
                     {"lambda_search_min", c.lambdaSearchMin},
                     {"lambda_search_max", c.lambdaSearchMax},
                     {"reference_dt_s", c.referenceDt_s},
                     {"max_step_fraction", c.maxStepFraction}};
}

void from_json(const nlohmann::json& j, Dmp::Options& c) {
  const std::string ctx = "DMP config";
  const std::string mode = core::requireField(j, "mode", ctx).get<std::string>();
  if (mode == "reference") c.mode = Dmp::Options::Mode::Reference;
  else if (mode == "default") c.mode = Dmp::Options::Mode::Default;
  else throw core::InvalidInputError(ctx + ": unknown mode '" + mode + "' (reference or default)");
  c.basisCount = core::requireField(j, "basis_count", ctx).get<int>();
  c.alpha_y = core::requireField(j, "alpha_y", ctx).get<double>();
  c.beta_y = core::requireField(j, "beta_y", ctx).get<double>();
  c.alpha_z = core::requireField(j, "alpha_z", ctx).get<double>();
  c.overlap = core::requireField(j, "overlap", ctx).get<double>();
  c.scaling = forcingScalingFromString(core::requireField(j, "scaling", ctx).get<std::string>());
  const auto& lam = core::requireField(j, "lambda", ctx);
  c.lambda = lam.is_null() ? std::nullopt : std::optional<double>(lam.get<double>());
  c.lambdaSearchMin = core::requireField(j, "lambda_search_min", ctx).get<double>();
  c.lambdaSearchMax = core::requireField(j, "lambda_search_max", ctx).get<double>();
  c.referenceDt_s = core::requireField(j, "reference_dt_s", ctx).get<double>();
  c.maxStepFraction = core::requireField(j, "max_step_fraction", ctx).get<double>();
  c.validate();
}

Dmp Dmp::imitate(const Eigen::VectorXd& t_s, const Eigen::MatrixXd& Y, const Options& config) {
  config.validate();
  validateDemo(t_s, Y);
  const bool reference = config.mode == Options::Mode::Reference;
  const Eigen::Index N = Y.rows(), D = Y.cols();
  const double tau = t_s(N - 1) - t_s(0);
  const detail::ForcingBasis basis(config.basisCount, config.alpha_z, config.overlap);

  Dmp dmp;
  dmp.config_ = config;
  dmp.demoDuration_s_ = tau;
  dmp.demoDt_s_ = tau / static_cast<double>(N - 1);
  dmp.demoStart_ = Y.row(0).transpose();
  dmp.demoGoal_ = Y.row(N - 1).transpose();

  // Derivatives as movement_primitives' determine_forces: np.gradient(Y) / np.gradient(T).
  const Eigen::MatrixXd DT = detail::numpyGradient(t_s);
  Eigen::MatrixXd Yd = detail::numpyGradient(Y);
  for (Eigen::Index d = 0; d < D; ++d) Yd.col(d) = Yd.col(d).cwiseQuotient(DT.col(0));
  if (reference) Yd.row(N - 1).setZero();
  Eigen::MatrixXd Ydd = detail::numpyGradient(Yd);
  for (Eigen::Index d = 0; d < D; ++d) Ydd.col(d) = Ydd.col(d).cwiseQuotient(DT.col(0));
  if (reference) Ydd.row(N - 1).setZero();

  const Eigen::RowVectorXd g = Y.row(N - 1);
  const double a = config.alpha_y, b = config.beta_y;
  Eigen::MatrixXd F, A;  // forcing targets (M x D), design matrix (M x K)
  Eigen::VectorXd Z, Tfit;
  if (reference) {
    F.resize(N, D), A.resize(N, config.basisCount), Z.resize(N);
    Tfit = t_s;
    for (Eigen::Index i = 0; i < N; ++i)
      F.row(i) = tau * tau * Ydd.row(i) - a * (b * (g - Y.row(i)) - tau * Yd.row(i));
  } else {
    // Targets from a cubic spline through the demo, sampled densely: its
    // derivatives are consistent with the positions, so integrating the
    // fitted system reproduces the demo.
    const detail::CubicSpline spline(t_s, Y);
    const Eigen::Index M = std::max<Eigen::Index>(N, 10 * config.basisCount);
    F.resize(M, D), A.resize(M, config.basisCount), Z.resize(M), Tfit.resize(M);
    Yd.resize(M, D), Ydd.resize(M, D);
    Eigen::MatrixXd Ys(M, D);
    for (Eigen::Index i = 0; i < M; ++i) {
      Tfit(i) = t_s(0) + tau * static_cast<double>(i) / static_cast<double>(M - 1);
      spline.evaluate(Tfit(i), Ys.row(i), Yd.row(i), Ydd.row(i));
    }
    const Eigen::RowVectorXd gd = Yd.row(M - 1);
    for (Eigen::Index i = 0; i < M; ++i)
      F.row(i) = tau * tau * Ydd.row(i) - a * (b * (g - Ys.row(i)) + tau * (gd - Yd.row(i)));
  }
  for (Eigen::Index i = 0; i < F.rows(); ++i) {
    Z(i) = basis.phase((Tfit(i) - t_s(0)) / tau);
    basis.activations(Z(i), A.row(i).transpose());
  }
  dmp.targets_ = {Z, Yd, Ydd, F};

  if (reference) {
    // w = pinv(X X^T + lambda I) X F, as the library (X = A^T).
    const Eigen::MatrixXd gram =
        A.transpose() * A + *config.lambda * Eigen::MatrixXd::Identity(A.cols(), A.cols());
    dmp.weights_ = (numpyPinv(gram) * A.transpose() * F).transpose();
    dmp.lambda_ = *config.lambda;
    dmp.demoStartVel_s_ = Eigen::VectorXd::Zero(D);
    dmp.demoGoalVel_s_ = Eigen::VectorXd::Zero(D);
  } else {
    const detail::RidgeSolver solver(A, F);
    if (config.lambda) {
      dmp.lambda_ = *config.lambda;
      dmp.gcv_ = solver.gcv(dmp.lambda_);
    } else {
      const auto choice = detail::chooseLambdaByGcv(solver, config.lambdaSearchMin, config.lambdaSearchMax);
      dmp.lambda_ = choice.lambda;
      dmp.gcv_ = choice.gcv;
    }
    dmp.weights_ = solver.weights(dmp.lambda_).transpose();
    dmp.demoStartVel_s_ = tau * Yd.row(0).transpose();
    dmp.demoGoalVel_s_ = tau * Yd.row(Yd.rows() - 1).transpose();
  }
  dmp.configure(dmp.demoStart_, dmp.demoGoal_, tau);
  return dmp;
}

void Dmp::configure(const Eigen::VectorXd& start, const Eigen::VectorXd& goal,
                    std::optional<double> duration_s, std::optional<Eigen::VectorXd> startVelocity,
                    std::optional<Eigen::VectorXd> goalVelocity) {
  const Eigen::Index D = weights_.rows();
  require(start.size() == D && goal.size() == D,
          "DMP configure: start and goal need " + std::to_string(D) + " coordinates");
  require(start.allFinite() && goal.allFinite(), "DMP configure: start or goal is NaN/infinite");
  if (duration_s)
    require(std::isfinite(*duration_s) && *duration_s > 0,
            "DMP configure: duration must be positive (got " + std::to_string(*duration_s) + " s)");
  start_ = start;
  goal_ = goal;
  if (duration_s) duration_s_ = *duration_s;
  if (config_.mode == Options::Mode::Reference) {
    startVel_s_ = goalVel_s_ = Eigen::VectorXd::Zero(D);
    return;
  }
  const Eigen::MatrixXd S = forcingScale();
  if (startVelocity) {
    require(startVelocity->size() == D && startVelocity->allFinite(), "DMP configure: bad start velocity");
    startVel_s_ = *startVelocity * duration_s_;
  } else {
    startVel_s_ = S * demoStartVel_s_;
  }
  if (goalVelocity) {
    require(goalVelocity->size() == D && goalVelocity->allFinite(), "DMP configure: bad goal velocity");
    goalVel_s_ = *goalVelocity * duration_s_;
  } else {
    goalVel_s_ = S * demoGoalVel_s_;
  }
}

Eigen::MatrixXd Dmp::forcingScale() const {
  const Eigen::Index D = weights_.rows();
  const Eigen::VectorXd demoDiff = demoGoal_ - demoStart_, diff = goal_ - start_;
  constexpr double kMinDisplacement_m = 1e-3;
  switch (config_.scaling) {
    case ForcingScaling::None: break;
    case ForcingScaling::PerDimension: {
      Eigen::VectorXd s = Eigen::VectorXd::Ones(D);
      for (Eigen::Index d = 0; d < D; ++d)
        if (std::abs(demoDiff(d)) >= kMinDisplacement_m) s(d) = diff(d) / demoDiff(d);
      return s.asDiagonal();
    }
    case ForcingScaling::Spatial: {
      if (demoDiff.norm() < kMinDisplacement_m || diff.norm() < kMinDisplacement_m) break;
      const double ratio = diff.norm() / demoDiff.norm();
      if (D != 3) return ratio * Eigen::MatrixXd::Identity(D, D);
      const Eigen::Vector3d from = demoDiff, to = diff;
      return ratio * Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
    }
  }
  return Eigen::MatrixXd::Identity(D, D);
}

DmpRollout Dmp::rollout() const {
  return rollout(config_.mode == Options::Mode::Reference ? config_.referenceDt_s
                                                           : demoDt_s_ * duration_s_ / demoDuration_s_);
}

DmpRollout Dmp::rollout(double dt_s) const {
  require(std::isfinite(dt_s) && dt_s > 0, "DMP rollout: dt must be positive (got " + std::to_string(dt_s) + ")");
  const Eigen::Index D = weights_.rows();
  const double tau = duration_s_;
  const double a = config_.alpha_y, b = config_.beta_y;
  const detail::ForcingBasis basis(config_.basisCount, config_.alpha_z, config_.overlap);
  Eigen::VectorXd act(config_.basisCount);
  auto forcing = [&](double t) -> Eigen::VectorXd {
    basis.activations(basis.phase(t / tau), act);
    return weights_ * act;
  };

  DmpRollout out;
  if (config_.mode == Options::Mode::Reference) {
    // movement_primitives dmp_open_loop + dmp_step_rk4: grid np.arange(0, tau + dt, dt),
    // start at rest, forcing at [t, t + dt/2, t + dt] with t the *new* time.
    const auto n = static_cast<Eigen::Index>(std::ceil((tau + dt_s) / dt_s));
    out.t_s.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) out.t_s(i) = static_cast<double>(i) * dt_s;
    out.y.resize(n, D);
    out.yd.resize(n, D);
    Eigen::VectorXd y = start_, yd = Eigen::VectorXd::Zero(D);
    out.y.row(0) = y.transpose();
    out.yd.row(0) = yd.transpose();
    const double tau2 = tau * tau;
    auto acc = [&](const Eigen::VectorXd& Y, const Eigen::VectorXd& V, const Eigen::VectorXd& f) {
      return Eigen::VectorXd((a * (b * (goal_ - Y) - tau * V) + f) / tau2);
    };
    for (Eigen::Index i = 1; i < n; ++i) {
      const double t = out.t_s(i), dt = t - out.t_s(i - 1), dt2 = 0.5 * dt;
      const Eigen::VectorXd F0 = forcing(t), F1 = forcing(t + dt2), F2 = forcing(t + dt);
      const Eigen::VectorXd C0 = yd;
      const Eigen::VectorXd K0 = acc(y, C0, F0);
      const Eigen::VectorXd C1 = yd + dt2 * K0;
      const Eigen::VectorXd K1 = acc(y + dt2 * C0, C1, F1);
      const Eigen::VectorXd C2 = yd + dt2 * K1;
      const Eigen::VectorXd K2 = acc(y + dt2 * C1, C2, F1);
      const Eigen::VectorXd C3 = yd + dt * K2;
      const Eigen::VectorXd K3 = acc(y + dt * C2, C3, F2);
      y += dt * (yd + dt / 6.0 * (K0 + K1 + K2));
      yd += dt / 6.0 * (K0 + 2 * K1 + 2 * K2 + K3);
      out.y.row(i) = y.transpose();
      out.yd.row(i) = yd.transpose();
    }
    return out;
  }

  // Default mode: classical RK4 in normalised time s = t / tau with the forcing
  // term at the stage times and sub-steps of at most maxStepFraction / (alpha / 2).
  const Eigen::MatrixXd SW = forcingScale() * weights_;
  const auto intervals = static_cast<Eigen::Index>(std::max(1.0, std::ceil(tau / dt_s - 1e-9)));
  const Eigen::Index n = intervals + 1;
  out.t_s.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) out.t_s(i) = std::min(static_cast<double>(i) * dt_s, tau);
  out.y.resize(n, D);
  out.yd.resize(n, D);
  const DefaultIntegration in{basis, SW, goal_, goalVel_s_, start_, startVel_s_, a, b, tau,
                              config_.maxStepFraction / (0.5 * a)};
  if (D == 3) integrateDefault<3>(in, out);
  else integrateDefault<Eigen::Dynamic>(in, out);
  return out;
}

Eigen::VectorXd Dmp::basisCenters() const {
  return detail::ForcingBasis(config_.basisCount, config_.alpha_z, config_.overlap).centers();
}
Eigen::VectorXd Dmp::basisWidths() const {
  return detail::ForcingBasis(config_.basisCount, config_.alpha_z, config_.overlap).widths();
}

nlohmann::json Dmp::toJson() const {
  using detail::toJson;
  nlohmann::json demo = endpointsJson(demoStart_, demoGoal_, demoStartVel_s_, demoGoalVel_s_, demoDuration_s_);
  demo["sample_period_s"] = demoDt_s_;
  return {{"class", "srp::motion::Dmp"},
          {"schema_version", 1},
          {"config", config_},
          {"weights", toJson(weights_)},
          {"lambda", lambda_},
          {"gcv_error", gcv_},
          {"demo", demo},
          {"configured", endpointsJson(start_, goal_, startVel_s_, goalVel_s_, duration_s_)}};
}

Dmp Dmp::fromJson(const nlohmann::json& j) {
  using core::requireField;
  using detail::matrixFromJson;
  const std::string ctx = "DMP JSON";
  detail::requireClassAndVersion(j, "srp::motion::Dmp", 1, ctx);
  Dmp dmp;
  dmp.config_ = requireField(j, "config", ctx).get<Options>();
  dmp.weights_ = matrixFromJson(requireField(j, "weights", ctx), ctx + " weights");
  require(dmp.weights_.cols() == dmp.config_.basisCount && dmp.weights_.rows() >= 1,
          ctx + ": weights must be D x basis_count");
  const Eigen::Index D = dmp.weights_.rows();
  dmp.lambda_ = requireField(j, "lambda", ctx).get<double>();
  dmp.gcv_ = requireField(j, "gcv_error", ctx).get<double>();
  const auto& demo = requireField(j, "demo", ctx);
  endpointsFromJson(demo, D, ctx + " demo", dmp.demoStart_, dmp.demoGoal_, dmp.demoStartVel_s_, dmp.demoGoalVel_s_,
                    dmp.demoDuration_s_);
  dmp.demoDt_s_ = requireField(demo, "sample_period_s", ctx).get<double>();
  endpointsFromJson(requireField(j, "configured", ctx), D, ctx + " configured", dmp.start_, dmp.goal_, dmp.startVel_s_,
                    dmp.goalVel_s_, dmp.duration_s_);
  require(dmp.duration_s_ > 0 && dmp.demoDuration_s_ > 0 && dmp.demoDt_s_ > 0,
          ctx + ": durations must be positive");
  require(dmp.weights_.allFinite(), ctx + ": weights contain NaN/inf");
  return dmp;
}

}  // namespace srp::motion
