// srp segment: grasp and release frames per object straight from a trajectory
// table (libs/motion), for data recorded by other systems.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "srp/core/Error.h"
#include "srp/core/Pose.h"
#include "srp/motion/RealTrackNoise.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/SyntheticPickPlace.h"
#include "srp/motion/TrajectoryTable.h"
#include "srp/synth/LabelledDemo.h"

namespace {

struct SegmentOptions {
  std::string trajectories;
  std::vector<std::string> order;
  double fps = 30.0;
  bool json = false;
  std::string writeExample;
  unsigned seed = 1;
  std::string events = "dwell";
  unsigned thesisSeed = 0;
  std::string noise = "detector";
};

void writeExample(const SegmentOptions& o) {
  if (o.noise == "real") {
    srp::motion::RealTrackNoise::Options c;
    c.seed = o.seed;
    const auto r = srp::motion::RealTrackNoise(c).apply(srp::synth::cleanLabelledDemo(o.seed));
    srp::motion::TrajectoryTable{r.noisy.hand, r.noisy.objects}.writeCsv(o.writeExample);
    std::cout << "wrote a synthetic demo with real-track noise (" << r.noisy.hand.size() << " frames at 30 FPS) to "
              << o.writeExample << "\nground truth (frames):\n";
    for (std::size_t i = 0; i < r.truth.planOrder.size(); ++i)
      std::cout << "  " << r.truth.planOrder[i] << ": grasp " << r.truth.graspIndex[i] << ", release "
                << r.truth.releaseIndex[i] << (r.nudgeIndex[i] >= 0 ? ", nudged at " + std::to_string(r.nudgeIndex[i]) : "")
                << "\n";
    std::cout << "segment it with: srp segment --trajectories " << o.writeExample << " --order ";
    for (std::size_t i = 0; i < r.truth.planOrder.size(); ++i) std::cout << (i ? "," : "") << r.truth.planOrder[i];
    std::cout << "\n";
    return;
  }
  srp::motion::SyntheticPickPlaceGenerator::Options c;
  c.seed = o.seed;
  const auto demo = srp::motion::SyntheticPickPlaceGenerator(c).generate();
  srp::motion::TrajectoryTable{demo.hand, demo.objects}.writeCsv(o.writeExample);
  std::cout << "wrote a synthetic demo (" << demo.hand.size() << " frames at 30 FPS) to " << o.writeExample
            << "\nground truth (frames):\n";
  for (std::size_t i = 0; i < demo.planOrder.size(); ++i)
    std::cout << "  " << demo.planOrder[i] << ": grasp " << demo.hand[demo.graspIndex[i]].frame << ", release "
              << demo.hand[demo.releaseIndex[i]].frame << "\n";
  std::cout << "segment it with: srp segment --trajectories " << o.writeExample << " --order ";
  for (std::size_t i = 0; i < demo.planOrder.size(); ++i) std::cout << (i ? "," : "") << demo.planOrder[i];
  std::cout << "\n";
}

void runSegment(const SegmentOptions& o) {
  if (!o.writeExample.empty()) {
    writeExample(o);
    return;
  }
  if (o.trajectories.empty()) throw srp::core::InvalidInputError("give --trajectories <csv> (or --write-example <csv>)");
  if (o.order.empty()) throw srp::core::InvalidInputError("give --order with the objects in plan order, e.g. --order cuboid,star");
  const auto table = srp::motion::TrajectoryTable::readCsv(o.trajectories, o.fps);
  srp::motion::Segmenter::Options config;
  using Events = srp::motion::Segmenter::EventEstimator;
  config.events = o.events == "thesis" ? Events::ThesisPublished : o.events == "fig6.10" ? Events::Thesis : Events::HandDwellBoundary;
  config.thesisSeed = o.thesisSeed;
  const auto seg = srp::motion::Segmenter(config).segment(table.hand, table.objects, o.order);
  if (o.json) {
    nlohmann::json objects = nlohmann::json::array();
    for (const auto& s : seg.objects) {
      nlohmann::json j{{"name", s.name}, {"moved", s.moved}};
      j["grasp_frame"] = s.moved ? nlohmann::json(s.graspFrame) : nlohmann::json(nullptr);
      j["release_frame"] = s.moved ? nlohmann::json(s.releaseFrame) : nlohmann::json(nullptr);
      if (!s.note.empty()) j["note"] = s.note;
      if (s.moved && !std::isnan(s.outlierFraction)) {
        j["outlier_fraction"] = s.outlierFraction;
        j["release_margin"] = s.releaseMargin;
        j["release_cue_gap_frames"] = s.releaseCueGap;
        j["confidence"] = s.lowConfidence ? "low" : "high";
        j["grasp_confidence"] = s.graspLowConfidence ? "low" : "high";
        j["release_confidence"] = s.releaseLowConfidence ? "low" : "high";
      }
      objects.push_back(j);
    }
    std::cout << nlohmann::json{{"objects", objects}}.dump(2) << "\n";
    return;
  }
  std::cout << std::left << std::setw(18) << "object" << std::setw(8) << "grasp" << std::setw(9) << "release"
            << "confidence (outliers, release margin [nats], hand-vs-part release gap [frames])\n";
  for (const auto& s : seg.objects) {
    std::cout << std::setw(18) << s.name;
    if (!s.moved) {
      std::cout << std::setw(8) << "-" << "-   (" << s.note << ")\n";
      continue;
    }
    std::cout << std::setw(8) << s.graspFrame << std::setw(9) << s.releaseFrame;
    if (std::isnan(s.outlierFraction)) std::cout << "-";
    else
      std::cout << (!s.lowConfidence                                      ? "high "
                    : s.graspLowConfidence && s.releaseLowConfidence ? "LOW (grasp, release) "
                    : s.graspLowConfidence                          ? "LOW (grasp) "
                                                                    : "LOW (release) ")
                << "(" << std::fixed << std::setprecision(0)
                << 100 * s.outlierFraction << " %, " << std::setprecision(1) << s.releaseMargin << ", "
                << s.releaseCueGap << ")" << std::defaultfloat;
    std::cout << "\n";
  }
  for (const auto& w : seg.warnings) std::cerr << "srp segment: warning: " << w << "\n";
}

void setupSegment(CLI::App& app) {
  auto o = std::make_shared<SegmentOptions>();
  app.add_option("--trajectories", o->trajectories,
                 "CSV: frame,hand_x,hand_y,hand_z,<name>_x,<name>_y,<name>_z,<name>_rz,... (camera frame, m, rad; "
                 "0,0,0 = not detected)");
  app.add_option("--order", o->order, "Target objects in plan order, comma separated (e.g. cuboid,star)")
      ->delimiter(',');
  app.add_option("--fps", o->fps, "Frame rate of the table [Hz]")->check(CLI::Range(0.1, 1000.0))->capture_default_str();
  app.add_flag("--json", o->json,
               R"(Print {"objects":[{"name","grasp_frame","release_frame","outlier_fraction","release_margin","release_cue_gap_frames","confidence","grasp_confidence","release_confidence"}]} (confidence: "low" when either event's is))");
  app.add_option("--write-example", o->writeExample, "Write a synthetic 4-object demo table to this CSV and exit");
  app.add_option("--events", o->events,
                 "Grasp/release estimator: dwell (default, robust: grasp = end of the hand's rest at the part, release "
                 "= where the hand arrives closest to the part's final place, so a hover above it is part of the move; "
                 "part detections on the hand and ghosts of parts released earlier are ignored), thesis (the thesis' "
                 "published code: Kalman, 3-component GMM, first sample of the last sample's component, hand closest "
                 "to the initial position) or fig6.10 (the robustified thesis-like estimator without the hand's rests)")
      ->check(CLI::IsMember({"dwell", "thesis", "fig6.10"}))
      ->capture_default_str();
  app.add_option("--thesis-seed", o->thesisSeed,
                 "--events thesis: seed of the mixture's k-means initialisation (the thesis' code used a random one; "
                 "its release can change with it)")
      ->capture_default_str();
  app.add_option("--noise", o->noise,
                 "--write-example: detector (the motion module's generator: Gaussian noise, dropouts, flicker) or real "
                 "(the synth choreography with the real-track noise model: outliers, hand jumps, lingering, nudges, a "
                 "hover before each release, parts hidden under the hand, ghosts of the previous part)")
      ->check(CLI::IsMember({"detector", "real"}))
      ->capture_default_str();
  app.add_option("--seed", o->seed, "Random seed of --write-example")->capture_default_str();
  app.callback([o] { runSegment(*o); });
}

const srp::app::CommandRegistrar kReg{"segment", "Grasp and release frames per object from a trajectory table (CSV)",
                                      40, setupSegment};

}  // namespace
