#include "srp/execution/JointTrajectory.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/OutputFile.h"

namespace srp::execution {

JointTrajectory JointTrajectory::fromPositions(const std::vector<double>& t_s,
                                               const std::vector<JointVector>& q_rad) {
  if (t_s.size() != q_rad.size() || t_s.size() < 2)
    throw srp::core::InvalidInputError(
        "JointTrajectory::fromPositions: need >= 2 samples and as many times as positions (got " +
        std::to_string(t_s.size()) + " times, " + std::to_string(q_rad.size()) + " positions)");
  JointTrajectory tr;
  const std::size_t n = t_s.size();
  tr.samples_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(t_s[i]) || !q_rad[i].allFinite())
      throw srp::core::InvalidInputError("JointTrajectory::fromPositions: sample " + std::to_string(i) +
                                         " is not finite");
    if (i > 0 && !(t_s[i] > t_s[i - 1]))
      throw srp::core::InvalidInputError("JointTrajectory::fromPositions: time of sample " +
                                         std::to_string(i) + " does not increase");
    tr.samples_[i].t_s = t_s[i] - t_s[0];
    tr.samples_[i].q_rad = q_rad[i];
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double dt = t_s[i + 1] - t_s[i - 1];
    tr.samples_[i].qd_radps = (q_rad[i + 1] - q_rad[i - 1]) / dt;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double dt = t_s[i + 1] - t_s[i - 1];
    tr.samples_[i].qdd_radps2 = (tr.samples_[i + 1].qd_radps - tr.samples_[i - 1].qd_radps) / dt;
  }
  return tr;
}

JointTrajectory JointTrajectory::fromSamples(std::vector<JointTrajectorySample> samples) {
  if (samples.size() < 2)
    throw srp::core::InvalidInputError("JointTrajectory::fromSamples: need >= 2 samples (got " +
                                       std::to_string(samples.size()) + ")");
  const double t0 = samples.front().t_s;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    auto& s = samples[i];
    if (!std::isfinite(s.t_s) || !s.q_rad.allFinite() || !s.qd_radps.allFinite() || !s.qdd_radps2.allFinite())
      throw srp::core::InvalidInputError("JointTrajectory::fromSamples: sample " + std::to_string(i) + " is not finite");
    if (i > 0 && !(s.t_s > samples[i - 1].t_s))
      throw srp::core::InvalidInputError("JointTrajectory::fromSamples: time of sample " + std::to_string(i) +
                                         " does not increase");
  }
  for (auto& s : samples) s.t_s -= t0;
  JointTrajectory tr;
  tr.samples_ = std::move(samples);
  return tr;
}

JointTrajectory JointTrajectory::hold(const JointVector& q_rad, double duration_s) {
  return fromPositions({0.0, std::max(duration_s, 1e-3)}, {q_rad, q_rad});
}

JointTrajectorySample JointTrajectory::at(double t_s) const {
  if (samples_.empty()) throw srp::core::InvalidInputError("JointTrajectory::at: empty trajectory");
  if (t_s <= samples_.front().t_s) {
    JointTrajectorySample s = samples_.front();
    s.t_s = t_s;
    return s;
  }
  if (t_s >= samples_.back().t_s) {
    JointTrajectorySample s = samples_.back();
    s.t_s = t_s;
    s.qd_radps.setZero();
    s.qdd_radps2.setZero();
    return s;
  }
  const auto it = std::upper_bound(samples_.begin(), samples_.end(), t_s,
                                   [](double t, const JointTrajectorySample& s) { return t < s.t_s; });
  const JointTrajectorySample& b = *it;
  const JointTrajectorySample& a = *(it - 1);
  const double h = b.t_s - a.t_s, s = (t_s - a.t_s) / h;
  const double s2 = s * s, s3 = s2 * s;
  // Cubic Hermite basis and its derivatives.
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  const double d00 = (6 * s2 - 6 * s) / h, d10 = 3 * s2 - 4 * s + 1, d01 = (-6 * s2 + 6 * s) / h,
               d11 = 3 * s2 - 2 * s;
  JointTrajectorySample out;
  out.t_s = t_s;
  out.q_rad = h00 * a.q_rad + h10 * h * a.qd_radps + h01 * b.q_rad + h11 * h * b.qd_radps;
  out.qd_radps = d00 * a.q_rad + d10 * a.qd_radps + d01 * b.q_rad + d11 * b.qd_radps;
  out.qdd_radps2 = (1 - s) * a.qdd_radps2 + s * b.qdd_radps2;
  return out;
}

void JointTrajectory::append(const JointTrajectory& next) {
  if (next.empty()) return;
  if (samples_.empty()) {
    samples_ = next.samples_;
    return;
  }
  if ((next.samples_.front().q_rad - samples_.back().q_rad).norm() > 1e-6)
    throw srp::core::InvalidInputError("JointTrajectory::append: the next trajectory does not start "
                                       "where this one ends");
  const double t0 = samples_.back().t_s;
  for (std::size_t i = 1; i < next.samples_.size(); ++i) {
    JointTrajectorySample s = next.samples_[i];
    s.t_s += t0;
    samples_.push_back(s);
  }
}

void JointTrajectory::writeCsv(const std::string& path) const {
  std::ostringstream out;
  out << "t_s";
  for (int i = 1; i <= 6; ++i) out << ",q" << i << "_rad";
  for (int i = 1; i <= 6; ++i) out << ",qd" << i << "_radps";
  out << "\n" << std::setprecision(9);
  for (const auto& s : samples_) {
    out << s.t_s;
    for (int i = 0; i < 6; ++i) out << "," << s.q_rad[i];
    for (int i = 0; i < 6; ++i) out << "," << s.qd_radps[i];
    out << "\n";
  }
  srp::core::writeFileAtomically(path, out.str());
}

}  // namespace srp::execution
