#include "srp/motion/SkillLearner.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "srp/core/Error.h"

namespace srp::motion {
namespace {

using core::InvalidInputError;

constexpr double kMinApproachMotion_m = 0.005;
constexpr double kApproachLength_m = 0.03;

Eigen::Vector3d approachAxis(const core::PositionTrajectory& hand, int index, int window,
                             const Eigen::Vector3d& towards, const std::optional<Eigen::Vector3d>& fixed) {
  if (fixed) return fixed->normalized();
  // The direction the hand came from: back until it is kApproachLength_m away
  // (the hand rests at the grasp, so the last few samples carry only noise).
  const Eigen::Vector3d& p = hand[static_cast<std::size_t>(index)].p_m;
  for (int j = index - 1; j >= std::max(0, index - window); --j) {
    const Eigen::Vector3d motion = p - hand[static_cast<std::size_t>(j)].p_m;
    if (motion.norm() >= kApproachLength_m) return motion.normalized();
  }
  const Eigen::Vector3d toObject = towards - hand[static_cast<std::size_t>(index)].p_m;
  if (toObject.norm() >= kMinApproachMotion_m) return toObject.normalized();
  return Eigen::Vector3d::UnitZ();  // camera looking at the table: +z points into it
}

double medianYaw(const std::vector<double>& yaw, int index, int half) {
  if (yaw.empty()) return 0.0;
  std::vector<double> w;
  const int n = static_cast<int>(yaw.size());
  for (int i = std::max(0, index - half); i <= std::min(n - 1, index + half); ++i)
    if (std::isfinite(yaw[static_cast<std::size_t>(i)])) w.push_back(yaw[static_cast<std::size_t>(i)]);
  if (w.empty()) return 0.0;
  std::nth_element(w.begin(), w.begin() + static_cast<long>(w.size() / 2), w.end());
  return w[w.size() / 2];
}

Dmp learnSegment(const core::PositionTrajectory& hand, int from, int to, const Dmp::Options& config,
                 const std::string& what) {
  const int count = to - from + 1;
  if (count < 3)
    throw InvalidInputError(what + " spans " + std::to_string(std::max(count, 0)) +
                            " samples; a DMP needs at least 3 (check the grasp/release frames)");
  Eigen::VectorXd t(count);
  Eigen::MatrixXd Y(count, 3);
  for (int i = 0; i < count; ++i) {
    t(i) = hand[static_cast<std::size_t>(from + i)].t_s;
    Y.row(i) = hand[static_cast<std::size_t>(from + i)].p_m.transpose();
  }
  return Dmp::imitate(t, Y, config);
}

}  // namespace

std::vector<SkillSet> SkillLearner::learn(const Segmentation& seg, const std::vector<ObjectTrack>& objects) const {
  std::map<std::string, const ObjectTrack*> byName;
  for (const auto& o : objects) byName[o.name] = &o;
  const auto& hand = seg.hand;
  std::vector<SkillSet> out;
  int previousRelease = seg.firstHandIndex;
  for (const auto& o : seg.objects) {
    if (!o.moved) continue;
    SkillSet s;
    s.objectName = o.name;
    s.frame = hand.frame();
    s.approachOffset_m = options_.approachOffset_m;
    s.reachStartIndex = std::min(std::max(previousRelease, seg.firstHandIndex), o.graspIndex);
    s.graspIndex = o.graspIndex;
    s.releaseIndex = o.releaseIndex;
    s.reachStartFrame = hand[static_cast<std::size_t>(s.reachStartIndex)].frame;
    s.graspFrame = o.graspFrame;
    s.releaseFrame = o.releaseFrame;
    const auto it = byName.find(o.name);
    const std::vector<double> noYaw;
    const std::vector<double>& yaw = it != byName.end() ? it->second->yaw_rad : noYaw;
    if (!yaw.empty() && yaw.size() != hand.size())
      throw InvalidInputError("object '" + o.name + "': " + std::to_string(yaw.size()) + " yaw samples for " +
                              std::to_string(hand.size()) + " positions; give one per sample or none");

    const Eigen::Vector3d pg = hand[static_cast<std::size_t>(o.graspIndex)].p_m;
    const Eigen::Vector3d pr = hand[static_cast<std::size_t>(o.releaseIndex)].p_m;
    s.graspApproachAxis = approachAxis(hand, o.graspIndex, options_.approachWindow, o.p_initial_m, options_.approachAxis);
    s.releaseApproachAxis = approachAxis(hand, o.releaseIndex, options_.approachWindow, o.p_final_m, options_.approachAxis);
    const double yawGrasp = medianYaw(yaw, o.graspIndex, 3), yawRelease = medianYaw(yaw, o.releaseIndex, 3);
    const Eigen::Quaterniond qg(Eigen::AngleAxisd(yawGrasp, Eigen::Vector3d::UnitZ()));
    const Eigen::Quaterniond qr(Eigen::AngleAxisd(yawRelease, Eigen::Vector3d::UnitZ()));
    s.X_frame_grasp = core::makePose(pg, qg);
    s.X_frame_preGrasp = core::makePose(pg - options_.approachOffset_m * s.graspApproachAxis, qg);
    s.X_frame_release = core::makePose(pr, qr);
    s.X_frame_preRelease = core::makePose(pr - options_.approachOffset_m * s.releaseApproachAxis, qr);

    s.reach = learnSegment(hand, s.reachStartIndex, o.graspIndex, options_.dmp, "Reach of '" + o.name + "'");
    s.move = learnSegment(hand, o.graspIndex, o.releaseIndex, options_.dmp, "Move of '" + o.name + "'");
    if (!yaw.empty()) {
      const int count = o.releaseIndex - o.graspIndex + 1;
      Eigen::VectorXd t(count);
      std::vector<Eigen::Quaterniond> q;
      double previous = yaw[static_cast<std::size_t>(o.graspIndex)];
      for (int i = 0; i < count; ++i) {
        t(i) = hand[static_cast<std::size_t>(o.graspIndex + i)].t_s;
        double a = yaw[static_cast<std::size_t>(o.graspIndex + i)];
        if (!std::isfinite(a)) a = previous;
        previous = a;
        q.emplace_back(Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()));
      }
      s.moveOrientation = QuaternionDmp::imitate(t, q, options_.dmp);
    }
    previousRelease = o.releaseIndex;
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace srp::motion
