#pragma once
// Noise-free labelled demos from the synthetic-demo module's choreography
// (libs/synth planDemonstration: the thesis' default scene and instruction 1,
// the choreography the rendered demos use) and the error tables of the
// real-track noise tests (issue 18).
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <iostream>

#include "srp/motion/RealTrackNoise.h"
#include "srp/motion/Segmenter.h"
#include "srp/synth/DemoTimeline.h"
#include "srp/synth/PickPlacePlan.h"

namespace srp::motion::testing {

/// Palm and object positions in the camera frame, hand invalid (zeros) while
/// idle (out of view); truth = the timeline's events (grasp = first frame the
/// object moves with the hand, release = last such frame).
inline LabelledDemo cleanSynthDemo(std::uint32_t seed) {
  const auto scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  const auto catalogue = core::ObjectCatalogue::load(scene.cataloguePath);
  const auto steps = synth::groundPlan(synth::defaultPlanJson(), scene, catalogue);
  synth::DemoOptions options;
  options.seed = seed;
  const auto timeline = synth::planDemonstration(scene, catalogue, steps, synth::HandModel{}, options);
  const core::Pose3 X_camera_world = timeline.scene.X_world_camera.inverse();
  LabelledDemo demo;
  demo.hand = core::PositionTrajectory("camera");
  for (const auto& o : timeline.scene.objects) {
    ObjectTrack t;
    t.name = o.id;
    t.positions = core::PositionTrajectory("camera");
    demo.objects.push_back(t);
  }
  for (const auto& f : timeline.frames) {
    const bool inView = f.phase != "idle";
    demo.hand.append({f.index, f.t_s, inView ? Eigen::Vector3d(X_camera_world * f.X_world_hand.translation())
                                             : Eigen::Vector3d::Zero(), inView});
    for (std::size_t j = 0; j < demo.objects.size(); ++j) {
      const core::Pose3 X_camera_object = X_camera_world * f.X_world_objects[j];
      demo.objects[j].positions.append({f.index, f.t_s, X_camera_object.translation(), true});
      demo.objects[j].yaw_rad.push_back(core::yawOf(X_camera_object.linear()));
    }
  }
  for (const auto& e : timeline.events) {
    demo.planOrder.push_back(e.objectId);
    demo.graspIndex.push_back(e.graspFrame);
    demo.releaseIndex.push_back(e.releaseFrame);
  }
  return demo;
}

/// The tracks a segmenter sees (plan objects first, then the others, like a perception CSV).
inline RealTrackNoise::Result noisySynthDemo(std::uint32_t seed) {
  RealTrackNoise::Config c;
  c.seed = seed;
  return RealTrackNoise(c).apply(cleanSynthDemo(seed));
}

struct EventErrors {
  std::vector<int> grasp, release;  // estimate - truth, frames
  int demos = 0;                    // demos evaluated
  int within(int tol) const {
    int k = 0;
    for (int e : grasp) k += std::abs(e) <= tol;
    for (int e : release) k += std::abs(e) <= tol;
    return k;
  }
  int count() const { return static_cast<int>(grasp.size() + release.size()); }
  int worst() const {
    int w = 0;
    for (int e : grasp) w = std::max(w, std::abs(e));
    for (int e : release) w = std::max(w, std::abs(e));
    return w;
  }
};

}  // namespace srp::motion::testing

namespace srp::motion::testing {

/// Grasp/release errors of `config` on the noisy synth demos of `seeds`
/// (printed per event when `print`).
inline EventErrors evaluateNoisy(const std::vector<std::uint32_t>& seeds, const Segmenter::Config& config,
                                 const std::string& label, bool print) {
  EventErrors errors;
  for (std::uint32_t seed : seeds) {
    RealTrackNoise::Result r;
    try {
      r = noisySynthDemo(seed);
    } catch (const std::exception& e) {
      // The synth planner finds no free spot for some seeds: not a demo.
      if (print) std::cout << label << " seed " << seed << ": no demo (" << e.what() << ")\n";
      continue;
    }
    ++errors.demos;
    const auto seg = Segmenter(config).segment(r.noisy.hand, r.noisy.objects, r.noisy.planOrder);
    for (std::size_t k = 0; k < r.noisy.planOrder.size(); ++k) {
      const auto& o = seg.objects[k];
      const int g = o.moved ? o.graspIndex - r.truth.graspIndex[k] : 9999;
      const int rel = o.moved ? o.releaseIndex - r.truth.releaseIndex[k] : 9999;
      errors.grasp.push_back(g);
      errors.release.push_back(rel);
      if (print)
        std::cout << label << " seed " << seed << " " << o.name << ": grasp " << g << ", release " << rel
                  << (r.nudgeIndex[k] >= 0 ? " (nudged)" : "") << "\n";
    }
  }
  return errors;
}

inline std::vector<std::uint32_t> seedRange(std::uint32_t from, std::uint32_t count) {
  std::vector<std::uint32_t> s;
  for (std::uint32_t i = 0; i < count; ++i) s.push_back(from + i);
  return s;
}

}  // namespace srp::motion::testing
