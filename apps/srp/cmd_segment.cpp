// srp segment: grasp and release frames per object straight from a trajectory
// table (libs/motion), for data recorded by other systems.
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "CommandRegistry.h"
#include "srp/core/Error.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/SyntheticPickPlace.h"
#include "srp/motion/TrajectoryTable.h"

namespace {

struct SegmentOptions {
  std::string trajectories;
  std::vector<std::string> order;
  double fps = 30.0;
  bool json = false;
  std::string writeExample;
  unsigned seed = 1;
  std::string events = "dwell";
};

void writeExample(const SegmentOptions& o) {
  srp::motion::SyntheticPickPlaceConfig c;
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
  srp::motion::Segmenter::Config config;
  config.events = o.events == "thesis" ? srp::motion::Segmenter::EventEstimator::Thesis
                                       : srp::motion::Segmenter::EventEstimator::HandDwellBoundary;
  const auto seg = srp::motion::Segmenter(config).segment(table.hand, table.objects, o.order);
  if (o.json) {
    nlohmann::json objects = nlohmann::json::array();
    for (const auto& s : seg.objects) {
      nlohmann::json j{{"name", s.name}, {"moved", s.moved}};
      j["grasp_frame"] = s.moved ? nlohmann::json(s.graspFrame) : nlohmann::json(nullptr);
      j["release_frame"] = s.moved ? nlohmann::json(s.releaseFrame) : nlohmann::json(nullptr);
      if (!s.note.empty()) j["note"] = s.note;
      objects.push_back(j);
    }
    std::cout << nlohmann::json{{"objects", objects}}.dump(2) << "\n";
    return;
  }
  std::cout << std::left << std::setw(18) << "object" << std::setw(8) << "grasp" << "release\n";
  for (const auto& s : seg.objects) {
    std::cout << std::setw(18) << s.name;
    if (s.moved) std::cout << std::setw(8) << s.graspFrame << s.releaseFrame << "\n";
    else std::cout << std::setw(8) << "-" << "-   (" << s.note << ")\n";
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
  app.add_flag("--json", o->json, R"(Print {"objects":[{"name","grasp_frame","release_frame"}]})");
  app.add_option("--write-example", o->writeExample, "Write a synthetic 4-object demo table to this CSV and exit");
  app.add_option("--events", o->events,
                 "Grasp/release estimator: dwell (ends of the hand's rests at the object) or thesis "
                 "(hand closest to the initial position; first sample of the final mixture component)")
      ->check(CLI::IsMember({"dwell", "thesis"}))
      ->capture_default_str();
  app.add_option("--seed", o->seed, "Random seed of --write-example")->capture_default_str();
  app.callback([o] { runSegment(*o); });
}

const srp::app::CommandRegistrar kReg{"segment", "Grasp and release frames per object from a trajectory table (CSV)",
                                      40, setupSegment};

}  // namespace
