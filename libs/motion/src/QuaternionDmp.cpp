#include "srp/motion/QuaternionDmp.h"

#include <cmath>

#include "ForcingBasis.h"
#include "JsonEigen.h"
#include "LambdaSearch.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"

namespace srp::motion {
namespace {

using core::require;

/// 2 log(q): the rotation vector [rad] of q (shortest way).
Eigen::Vector3d rotationVector(Eigen::Quaterniond q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const double n = q.vec().norm();
  if (n < 1e-12) return 2.0 * q.vec();
  return 2.0 * std::atan2(n, q.w()) * q.vec() / n;
}

Eigen::Quaterniond fromRotationVector(const Eigen::Vector3d& r) {
  const double angle = r.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * r.x(), 0.5 * r.y(), 0.5 * r.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, r / angle));
}

Eigen::Vector4d toVec(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }

}  // namespace

QuaternionDmp QuaternionDmp::imitate(const Eigen::VectorXd& t_s, const std::vector<Eigen::Quaterniond>& qIn,
                                     const Dmp::Options& config) {
  config.validate();
  require(config.mode == Dmp::Options::Mode::Default, "QuaternionDmp: only Default mode exists for orientations");
  const auto N = static_cast<Eigen::Index>(qIn.size());
  require(t_s.size() == N, "QuaternionDmp demo: one time per orientation needed");
  require(N >= 3, "QuaternionDmp demo has " + std::to_string(N) + " samples; at least 3 are needed");
  require(t_s.allFinite(), "QuaternionDmp demo: non-finite time");
  for (Eigen::Index i = 0; i < N; ++i) {
    require(qIn[static_cast<std::size_t>(i)].coeffs().allFinite() && qIn[static_cast<std::size_t>(i)].norm() > 0.5,
            "QuaternionDmp demo: orientation " + std::to_string(i) + " is not a finite unit quaternion");
    if (i > 0) require(t_s(i) > t_s(i - 1), "QuaternionDmp demo: times must increase strictly");
  }
  // Sign-continuous unit quaternions.
  std::vector<Eigen::Quaterniond> q(qIn.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    q[i] = qIn[i].normalized();
    if (i > 0 && q[i].dot(q[i - 1]) < 0) q[i].coeffs() = -q[i].coeffs();
  }
  const double tau = t_s(N - 1) - t_s(0);
  // eta = tau omega by central differences of the rotation between neighbours, then d eta / ds.
  Eigen::MatrixXd eta(N, 3), etaDot(N, 3);
  for (Eigen::Index i = 0; i < N; ++i) {
    const Eigen::Index a = std::max<Eigen::Index>(i - 1, 0), b = std::min<Eigen::Index>(i + 1, N - 1);
    const double ds = (t_s(b) - t_s(a)) / tau;
    eta.row(i) = (rotationVector(q[static_cast<std::size_t>(b)] * q[static_cast<std::size_t>(a)].conjugate()) / ds).transpose();
  }
  for (Eigen::Index i = 0; i < N; ++i) {
    const Eigen::Index a = std::max<Eigen::Index>(i - 1, 0), b = std::min<Eigen::Index>(i + 1, N - 1);
    etaDot.row(i) = (eta.row(b) - eta.row(a)) / ((t_s(b) - t_s(a)) / tau);
  }
  const detail::ForcingBasis basis(config.basisCount, config.alpha_z, config.overlap);
  const Eigen::Quaterniond g = q.back();
  const Eigen::RowVector3d etaGoal = eta.row(N - 1);
  Eigen::MatrixXd F(N, 3), A(N, config.basisCount);
  for (Eigen::Index i = 0; i < N; ++i) {
    const Eigen::Vector3d toGoal = rotationVector(g * q[static_cast<std::size_t>(i)].conjugate());
    F.row(i) = etaDot.row(i) - config.alpha_y * (config.beta_y * toGoal.transpose() + (etaGoal - eta.row(i)));
    basis.activations(basis.phase((t_s(i) - t_s(0)) / tau), A.row(i).transpose());
  }
  QuaternionDmp dmp;
  dmp.config_ = config;
  const detail::RidgeSolver solver(A, F);
  dmp.lambda_ = config.lambda ? *config.lambda
                              : detail::chooseLambdaByGcv(solver, config.lambdaSearchMin, config.lambdaSearchMax).lambda;
  dmp.weights_ = solver.weights(dmp.lambda_).transpose();
  dmp.demoStart_ = q.front();
  dmp.demoGoal_ = g;
  dmp.demoStartEta_ = eta.row(0).transpose();
  dmp.demoGoalEta_ = etaGoal.transpose();
  dmp.demoDuration_s_ = tau;
  dmp.configure(dmp.demoStart_, dmp.demoGoal_, tau);
  return dmp;
}

void QuaternionDmp::configure(const Eigen::Quaterniond& start, const Eigen::Quaterniond& goal,
                              std::optional<double> duration_s, std::optional<Eigen::Vector3d> startOmega_radps,
                              std::optional<Eigen::Vector3d> goalOmega_radps) {
  require(start.coeffs().allFinite() && goal.coeffs().allFinite() && start.norm() > 0.5 && goal.norm() > 0.5,
          "QuaternionDmp configure: start and goal must be unit quaternions");
  if (duration_s) require(std::isfinite(*duration_s) && *duration_s > 0, "QuaternionDmp configure: duration must be positive");
  start_ = start.normalized();
  goal_ = goal.normalized();
  if (duration_s) duration_s_ = *duration_s;
  startEta_ = startOmega_radps ? Eigen::Vector3d(*startOmega_radps * duration_s_) : demoStartEta_;
  goalEta_ = goalOmega_radps ? Eigen::Vector3d(*goalOmega_radps * duration_s_) : demoGoalEta_;
}

QuaternionDmpRollout QuaternionDmp::rollout(double dt_s) const {
  require(std::isfinite(dt_s) && dt_s > 0, "QuaternionDmp rollout: dt must be positive");
  const double tau = duration_s_;
  const detail::ForcingBasis basis(config_.basisCount, config_.alpha_z, config_.overlap);
  Eigen::VectorXd act(config_.basisCount);
  const auto intervals = static_cast<Eigen::Index>(std::max(1.0, std::ceil(tau / dt_s - 1e-9)));
  const Eigen::Index n = intervals + 1;
  QuaternionDmpRollout out;
  out.t_s.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) out.t_s(i) = std::min(static_cast<double>(i) * dt_s, tau);
  out.q.resize(static_cast<std::size_t>(n));
  out.omega_radps.resize(n, 3);
  Eigen::Quaterniond q = start_;
  if (q.dot(goal_) < 0) q.coeffs() = -q.coeffs();
  Eigen::Vector3d eta = startEta_;
  out.q[0] = q;
  out.omega_radps.row(0) = (eta / tau).transpose();
  // Semi-implicit Euler on the unit sphere with small steps (the quaternion stays unit).
  const double maxStep = 0.2 * config_.maxStepFraction / (0.5 * config_.alpha_y);
  for (Eigen::Index i = 1; i < n; ++i) {
    const double s0 = out.t_s(i - 1) / tau, s1 = out.t_s(i) / tau;
    const int m = std::max(1, static_cast<int>(std::ceil((s1 - s0) / maxStep - 1e-12)));
    const double h = (s1 - s0) / m;
    for (int k = 0; k < m; ++k) {
      const double s = s0 + (k + 0.5) * h;
      basis.activations(basis.phase(s), act);
      const Eigen::Vector3d f = weights_ * act;
      const Eigen::Vector3d etaDot =
          config_.alpha_y * (config_.beta_y * rotationVector(goal_ * q.conjugate()) + (goalEta_ - eta)) + f;
      eta += h * etaDot;
      q = (fromRotationVector(h * eta) * q).normalized();
    }
    out.q[static_cast<std::size_t>(i)] = q;
    out.omega_radps.row(i) = (eta / tau).transpose();
  }
  return out;
}

nlohmann::json QuaternionDmp::toJson() const {
  using detail::toJson;
  return {{"class", "srp::motion::QuaternionDmp"},
          {"schema_version", 1},
          {"config", config_},
          {"weights", toJson(weights_)},
          {"lambda", lambda_},
          {"demo", {{"start_wxyz", toJson(Eigen::VectorXd(toVec(demoStart_)))},
                    {"goal_wxyz", toJson(Eigen::VectorXd(toVec(demoGoal_)))},
                    {"start_eta", toJson(Eigen::VectorXd(demoStartEta_))},
                    {"goal_eta", toJson(Eigen::VectorXd(demoGoalEta_))},
                    {"duration_s", demoDuration_s_}}},
          {"configured", {{"start_wxyz", toJson(Eigen::VectorXd(toVec(start_)))},
                          {"goal_wxyz", toJson(Eigen::VectorXd(toVec(goal_)))},
                          {"start_eta", toJson(Eigen::VectorXd(startEta_))},
                          {"goal_eta", toJson(Eigen::VectorXd(goalEta_))},
                          {"duration_s", duration_s_}}}};
}

QuaternionDmp QuaternionDmp::fromJson(const nlohmann::json& j) {
  using core::requireField;
  const std::string ctx = "QuaternionDmp JSON";
  detail::requireClassAndVersion(j, "srp::motion::QuaternionDmp", 1, ctx);
  QuaternionDmp dmp;
  dmp.config_ = requireField(j, "config", ctx).get<Dmp::Options>();
  dmp.weights_ = detail::matrixFromJson(requireField(j, "weights", ctx), ctx + " weights");
  require(dmp.weights_.rows() == 3 && dmp.weights_.cols() == dmp.config_.basisCount, ctx + ": weights must be 3 x basis_count");
  dmp.lambda_ = requireField(j, "lambda", ctx).get<double>();
  const auto& d = requireField(j, "demo", ctx);
  // Stored quaternions are not re-normalised beyond rounding: they were written normalised.
  auto quat = [&](const nlohmann::json& o, const char* key) {
    const Eigen::VectorXd v = detail::vectorFromJson(requireField(o, key, ctx), 4, ctx);
    return Eigen::Quaterniond(v(0), v(1), v(2), v(3));
  };
  dmp.demoStart_ = quat(d, "start_wxyz");
  dmp.demoGoal_ = quat(d, "goal_wxyz");
  dmp.demoStartEta_ = detail::vectorFromJson(requireField(d, "start_eta", ctx), 3, ctx);
  dmp.demoGoalEta_ = detail::vectorFromJson(requireField(d, "goal_eta", ctx), 3, ctx);
  dmp.demoDuration_s_ = requireField(d, "duration_s", ctx).get<double>();
  const auto& c = requireField(j, "configured", ctx);
  dmp.start_ = quat(c, "start_wxyz");
  dmp.goal_ = quat(c, "goal_wxyz");
  dmp.startEta_ = detail::vectorFromJson(requireField(c, "start_eta", ctx), 3, ctx);
  dmp.goalEta_ = detail::vectorFromJson(requireField(c, "goal_eta", ctx), 3, ctx);
  dmp.duration_s_ = requireField(c, "duration_s", ctx).get<double>();
  require(dmp.duration_s_ > 0 && dmp.demoDuration_s_ > 0, ctx + ": durations must be positive");
  return dmp;
}

}  // namespace srp::motion
