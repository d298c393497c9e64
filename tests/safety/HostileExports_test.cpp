// Exported robot programs are data, never text that can escape: every string a
// user or a file puts into an export (task name, instruction, scene path, step
// objects, relations and reasons, part names, joint names, frame id, topic) is
// replaced by 1000+ hostile strings, and every file is read back as its
// consumer reads it: URScript by a tokenizer (no byte a controller could take
// for a line break, the same statements as a clean export), the ROS 2 YAML by
// PyYAML's load_all as `ros2 topic pub --yaml-file` does (exactly one document,
// the same data as a clean export).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "HostileStrings.h"
#include "ScratchFolder.h"
#include "srp/core/Error.h"
#include "srp/execution/ExecutedTask.h"
#include "srp/execution/RobotModel.h"
#include "srp/execution/RosTrajectoryExporter.h"
#include "srp/execution/UrScriptExporter.h"

namespace fs = std::filesystem;
using namespace srp::execution;

namespace {

constexpr std::size_t kHostileCases = 1200;

/// A small exportable task: a 0.12 s minimum-jerk move of every joint (12 knots),
/// one done step, one skipped step with a reason, a grasp and a release.
ExecutedTask smallTask() {
  const RobotModel robot = RobotModel::defaultUr5();
  ExecutedTask t;
  for (int i = 0; i < 6; ++i) t.jointNames[i] = robot.joints()[i].name;
  t.lower_rad = robot.lowerLimits_rad();
  t.upper_rad = robot.upperLimits_rad();
  t.maxVelocity_radps = robot.maxVelocities_radps();
  t.maxAcceleration_radps2 = 5.0;
  const JointVector q0(0.1, -1.2, 1.1, -1.4, -1.57, 0.2);
  std::vector<double> times;
  std::vector<JointVector> q;
  constexpr int kKnots = 13;
  constexpr double kDuration_s = 0.12, kMove_rad = 0.004;
  for (int k = 0; k < kKnots; ++k) {
    const double s = static_cast<double>(k) / (kKnots - 1);
    times.push_back(s * kDuration_s);
    q.push_back(q0 + JointVector::Constant(kMove_rad * s * s * s * (10 - 15 * s + 6 * s * s)));
  }
  t.trajectory = JointTrajectory::fromPositions(times, q);
  StepReport done;
  done.index = 0;
  done.object = "cuboid";
  done.relation = "in gray box";
  done.status = StepStatus::Done;
  StepReport skipped;
  skipped.index = 1;
  skipped.object = "star";
  skipped.relation = "next to cuboid";
  skipped.status = StepStatus::Skipped;
  skipped.reason = "the star is not in the scene";
  t.report.steps = {done, skipped};
  t.gripperEvents = {{GripperEvent::Kind::Grasp, 0.0, "cuboid"}, {GripperEvent::Kind::Release, 0.12, "cuboid"}};
  t.taskName = "thesis";
  t.taskModelId = 1;
  t.instruction = "Pick up the cuboid and place it in the gray box.";
  t.scene = "sim/scenes/default.json";
  return t;
}

/// Every text field of an export set to `s` (joint names separately).
ExecutedTask withText(ExecutedTask t, const std::string& s) {
  t.taskName = t.instruction = t.scene = s;
  for (auto& step : t.report.steps) step.object = step.relation = s;
  t.report.steps[1].reason = s;
  for (auto& e : t.gripperEvents) e.part = s;
  return t;
}

/// The URScript tokenizer: the statements of a program, one token list per line,
/// comments (from '#' outside a string literal to the end of the line) dropped.
/// Fails (returns nullopt with `why`) on any byte a controller could take for a
/// line break or that is not printable ASCII.
std::optional<std::vector<std::vector<std::string>>> statements(const std::string& script, std::string& why) {
  std::vector<std::vector<std::string>> lines(1);
  std::string token;
  bool comment = false, inString = false;
  const auto flush = [&] {
    if (!token.empty()) lines.back().push_back(token);
    token.clear();
  };
  for (std::size_t i = 0; i < script.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(script[i]);
    if (c == '\n') {
      flush();
      if (inString) return why = "a string literal runs over a line end", std::nullopt;
      comment = false;
      lines.emplace_back();
      continue;
    }
    if (c < 0x20 || c > 0x7E) {
      char buffer[64];
      std::snprintf(buffer, sizeof(buffer), "byte 0x%02X at offset %zu", c, i);
      return why = buffer, std::nullopt;
    }
    if (comment) continue;
    if (inString) {
      token += static_cast<char>(c);
      if (c == '"') inString = false, flush();
      continue;
    }
    if (c == '#') {
      flush();
      comment = true;
    } else if (c == '"') {
      flush();
      token = "\"";
      inString = true;
    } else if (std::isalnum(c) || c == '_' || c == '.' || (c == '-' && token.empty())) {
      token += static_cast<char>(c);
    } else {
      flush();
      if (c != ' ') lines.back().push_back(std::string(1, static_cast<char>(c)));
    }
  }
  flush();
  std::vector<std::vector<std::string>> code;
  for (auto& l : lines)
    if (!l.empty()) code.push_back(std::move(l));
  return code;
}

}  // namespace

TEST(HostileExports, NoStringAddsAUrScriptStatement) {
  const ExecutedTask clean = smallTask();
  const UrScriptExporter exporter;
  std::string why;
  const auto reference = statements(exporter.toScript(clean), why);
  ASSERT_TRUE(reference) << why;
  int escaped = 0, cases = 0;
  for (const std::string& s : srp::safety::hostileStrings(kHostileCases)) {
    for (int field = 0; field < 2; ++field) {
      ExecutedTask t = field == 0 ? withText(clean, s) : clean;
      if (field == 1) t.jointNames.fill(s);
      ++cases;
      const auto code = statements(exporter.toScript(t), why);
      if (!code || *code != *reference) {
        ++escaped;
        ADD_FAILURE() << "case " << cases << (field ? " (joint names)" : "") << ": "
                      << (code ? "the statements differ" : why);
      }
    }
  }
  std::printf("[ sweep ] URScript: %d hostile exports, %d escaped\n", cases, escaped);
  EXPECT_EQ(escaped, 0);
}

TEST(HostileExports, EveryYamlIsOneDocumentWithTheCheckedData) {
  const ExecutedTask clean = smallTask();
  const srp::safety::ScratchFolder dir("yaml");
  RosTrajectoryExporter::Options options;
  const RosTrajectoryExporter plain(options);
  const fs::path reference = dir.path / "reference.yaml";
  std::ofstream(reference) << plain.toYaml(clean);
  std::vector<std::string> files;
  const auto hostile = srp::safety::hostileStrings(kHostileCases);
  int cases = 0, notAscii = 0;
  for (std::size_t i = 0; i < hostile.size(); ++i)
    for (int field = 0; field < 2; ++field) {
      ExecutedTask t = field == 0 ? withText(clean, hostile[i]) : clean;
      RosTrajectoryExporter::Options o;
      if (field == 0) {
        o.topic = hostile[i];
      } else {
        t.jointNames.fill(hostile[i]);
        o.frameId = hostile[i];
      }
      const std::string text = RosTrajectoryExporter(o).toYaml(t);
      for (char c : text) notAscii += (c != '\n' && (c < 0x20 || c > 0x7E)) ? 1 : 0;
      const fs::path file = dir.path / ("case_" + std::to_string(cases++) + ".yaml");
      std::ofstream(file, std::ios::binary) << text;
      files.push_back(file.string());
    }
  EXPECT_EQ(notAscii, 0) << "bytes that are not printable ASCII in the YAML files";
  // PyYAML over every file, in one process (the argument list goes through a file list).
  const fs::path list = dir.path / "files.txt";
  {
    std::ofstream out(list);
    for (const auto& f : files) out << f << "\n";
  }
  const std::string command = "xargs -a '" + list.string() + "' python3 '" + std::string(SRP_SOURCE_DIR) +
                              "/tests/safety/read_exports.py' '" + reference.string() + "' > '" +
                              (dir.path / "result.json").string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << "python3 with PyYAML (python3-yaml) is needed: " << command;
  // xargs may split the list over several runs: one JSON line each.
  int read = 0, oneDocument = 0, equal = 0;
  std::ifstream results(dir.path / "result.json");
  for (std::string line; std::getline(results, line);) {
    const auto j = nlohmann::json::parse(line);
    read += j.at("files").get<int>();
    oneDocument += j.at("one_document").get<int>();
    equal += j.at("equal_data").get<int>();
    for (const auto& f : j.at("failures")) ADD_FAILURE() << f.dump();
  }
  std::printf("[ sweep ] ROS 2 YAML: %d hostile exports read by PyYAML, %d with one document, %d with the checked data\n",
              read, oneDocument, equal);
  EXPECT_EQ(read, cases);
  EXPECT_EQ(oneDocument, cases);
  EXPECT_EQ(equal, cases);
}

TEST(HostileExports, ProgramNamesAreUrScriptIdentifiersOnly) {
  int refused = 0, accepted = 0;
  for (const std::string& s : srp::safety::hostileStrings(kHostileCases)) {
    UrScriptExporter::Options o;
    o.programName = s;
    try {
      UrScriptExporter e(o);
      ++accepted;
      std::string why;
      EXPECT_TRUE(statements(e.toScript(smallTask()), why)) << why;
    } catch (const srp::core::InvalidInputError&) {
      ++refused;
    }
  }
  std::printf("[ sweep ] URScript program names: %d refused, %d accepted (identifiers)\n", refused, accepted);
  EXPECT_GT(refused, static_cast<int>(kHostileCases) - 60);
}

// --ros-point-period: a thinned trajectory is checked again (limits, 5 mrad from
// the checked one) or nothing is written; never "safety-checked" text on an
// unchecked path. Any period (1e6 included) keeps the knots the checks need;
// a naively thinned trajectory (every n-th knot) is refused by the same check.
TEST(RosThinning, EveryPeriodIsCheckedOrRefused) {
  // A 2 s move of up to 0.8 rad (not the tiny task above).
  ExecutedTask t = smallTask();
  std::vector<double> times;
  std::vector<JointVector> q;
  const JointVector q0(0.1, -1.2, 1.1, -1.4, -1.57, 0.2);
  for (int k = 0; k <= 200; ++k) {
    const double s = k / 200.0;
    times.push_back(2.0 * s);
    // A 2 Hz, 20 mrad wobble on the wrist (3.2 rad/s^2): thinning has something to lose.
    JointVector wobble = JointVector::Zero();
    wobble[4] = 0.02 * std::sin(2.0 * M_PI * 2.0 * (2.0 * s)) * std::sin(M_PI * s);
    q.push_back(q0 + JointVector(0.8, -0.3, 0.5, 0.2, -0.4, 0.6) * (s * s * s * (10 - 15 * s + 6 * s * s)) + wobble);
  }
  t.trajectory = JointTrajectory::fromPositions(times, q);
  t.gripperEvents.back().t_s = 2.0;
  int written = 0, refused = 0, badOption = 0;
  for (double period : std::vector<double>{0.0, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 1e6, HUGE_VAL, std::nan(""), -1.0}) {
    RosTrajectoryExporter::Options o;
    o.pointPeriod_s = period;
    try {
      const RosTrajectoryExporter e(o);
      try {
        e.toYaml(t);
        ++written;
        const JointTrajectory exported = e.exportedTrajectory(t);
        EXPECT_LE(RosTrajectoryExporter::deviation_rad(exported, t.trajectory), o.maxThinningDeviation_rad) << period;
        EXPECT_FALSE(e.checkThinned(t, exported)) << period;
      } catch (const srp::core::InvalidInputError& err) {
        ++refused;
        EXPECT_NE(std::string(err.what()).find("--ros-point-period"), std::string::npos) << err.what();
      }
    } catch (const srp::core::InvalidInputError&) {
      ++badOption;  // inf, nan, negative: refused as options
    }
  }
  // Every 40th knot (0.4 s apart): the check itself refuses it.
  std::vector<JointTrajectorySample> naive;
  for (std::size_t k = 0; k < t.trajectory.samples().size(); k += 40) naive.push_back(t.trajectory.samples()[k]);
  RosTrajectoryExporter::Options o;
  o.pointPeriod_s = 0.4;
  const auto why = RosTrajectoryExporter(o).checkThinned(t, JointTrajectory::fromSamples(naive));
  EXPECT_TRUE(why.has_value());
  std::printf("[ sweep ] --ros-point-period: %d periods written (checked again), %d refused after the check, %d bad "
              "options; every 40th knot: %s\n",
              written, refused, badOption, why ? why->c_str() : "passed (wrong)");
  EXPECT_EQ(written, 9);
  EXPECT_EQ(badOption, 3);
}
