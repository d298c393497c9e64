// The own-recording run (OwnRecording_test) under the marker-free hand's
// label-preserving perturbations of HRT1 task2 and task3 (Hrt1Palms.h
// hrt1Perturbations: light, white balance, JPEG, colour and depth noise,
// depth holes, other intrinsics, a turned or mirrored camera, 5 Hz): each
// perturbed recording is written as a rawlog and programmed with "Pick up
// the toy and put it in the bin." as `srp program` does. A case succeeds when
// one step is stored with the toy moved, grasp and release within
// kEventTol_frames of our labels (event_labels.json; at 5 Hz the frames kept,
// in the original numbering) and the toy's last pose inside the bin's
// footprint. Slow label: 42 recordings programmed (~5 s each, ~4 min).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "Hrt1Palms.h"
#include "srp/programming/ProgrammingPipeline.h"
#include "srp/rawlog/RawlogWriter.h"
#include "srp/taskdb/TaskDatabase.h"
#include "srp/taskdb/TaskModelStore.h"

namespace srp {
namespace {

constexpr int kEventTol_frames = 2;  // as OwnRecording_test (issue 30: within 2 frames at 10 Hz)
// Issue 30: >= 90 % of the perturbed cases succeed (39/42 measured, see the
// programming README).
constexpr double kMinSuccessRate = 0.9;

struct Outcome {
  bool ok = false;
  std::string why;
};

Outcome programPerturbed(const perception::testing::Hrt1Task& t, const std::string& db, const std::string& rawlog) {
  {
    rawlog::RawlogWriter w(rawlog, 1e-3);
    for (auto f : t.frames) {
      f.t_s = f.index / 10.0;  // HRT1 is about 10 Hz; the frame keeps its original number
      w.write(f);
    }
  }
  programming::ProgrammingOptions o;
  o.instruction = "Pick up the toy and put it in the bin.";
  o.demoPath = rawlog;
  o.dbPath = db;
  std::filesystem::remove(db);
  programming::ProgramResult r;
  try {
    r = programming::programTask(o);
  } catch (const std::exception& e) {
    return {false, e.what()};
  }
  if (r.objects.size() != 1 || !r.objects[0].moved) return {false, "no moved toy"};
  const auto labels = core::readJsonFile(perception::testing::hrt1Root() + "/event_labels.json").at("tasks").at(t.name);
  // The reader numbers the kept frames 0, 1, ...: back to the recording's numbers.
  const auto original = [&](int k) { return k >= 0 && k < static_cast<int>(t.frames.size()) ? t.frames[k].index : -99; };
  const int grasp = original(r.objects[0].graspFrame), release = original(r.objects[0].releaseFrame);
  const int tol = kEventTol_frames + (t.frames.size() < 30 ? 1 : 0);  // 5 Hz: the nearest kept frame may be 1 off
  if (std::abs(grasp - labels.at("grasp_frame").get<int>()) > tol ||
      std::abs(release - labels.at("release_frame").get<int>()) > tol)
    return {false, "grasp " + std::to_string(grasp) + ", release " + std::to_string(release)};
  const core::ObjectClass* bin = nullptr;
  for (const auto& c : r.observedClasses)
    if (c.name == "bin") bin = &c;
  if (!bin) return {false, "no bin"};
  auto database = taskdb::TaskDatabase::open(db, taskdb::TaskDatabase::Mode::ReadOnly);
  const taskdb::TaskModel model = taskdb::TaskModelStore(database).read(r.taskModelId);
  const taskdb::ProductPoseRow *toyLast = nullptr, *binRow = nullptr;
  for (const auto& p : model.productPoses) {
    if (p.classId == r.objects[0].classId && p.detected && (!toyLast || p.timeId > toyLast->timeId)) toyLast = &p;
    if (p.classId == bin->classId && p.detected && !binRow) binRow = &p;
  }
  if (!toyLast || !binRow) return {false, "no stored poses"};
  const Eigen::Vector3d p = core::makePose(binRow->p_m, binRow->q).inverse() * toyLast->p_m;
  if (std::abs(p.x()) >= bin->dimensions_m.x() / 2 || std::abs(p.y()) >= bin->dimensions_m.y() / 2)
    return {false, "toy outside the bin"};
  return {true, "grasp " + std::to_string(grasp) + ", release " + std::to_string(release)};
}

TEST(OwnRecording, Hrt1UnderPerturbations) {
  const auto dir = std::filesystem::path(SRP_BINARY_DIR) / "acceptance_own_recording_perturbed";
  std::filesystem::create_directories(dir);
  int cases = 0, ok = 0;
  for (const std::string task : {"task2", "task3"}) {
    if (const char* only = std::getenv("SRP_OWN_TASK"); only && task != only) continue;  // one recording, to look at
    const perception::testing::Hrt1Task original = perception::testing::loadHrt1(task);
    for (const auto& p : perception::testing::hrt1Perturbations()) {
      if (const char* only = std::getenv("SRP_OWN_PERTURBATION"); only && p.name != only) continue;  // one case, to look at
      perception::testing::Hrt1Task t = original;  // a copy with its own images: the perturbation changes them
      for (auto& f : t.frames) {
        f.colour_bgr8 = f.colour_bgr8.clone();
        f.depth_m = f.depth_m.clone();
      }
      p.apply(t);
      const Outcome out = programPerturbed(t, (dir / "t.db").string(), (dir / "t.rawlog").string());
      ++cases;
      ok += out.ok ? 1 : 0;
      std::printf("[ figures  ] HRT1 %s, %-26s %s: %s\n", task.c_str(), p.name.c_str(), out.ok ? "ok  " : "FAIL",
                  out.why.substr(0, std::getenv("SRP_OWN_PERTURBATION") ? std::string::npos : 160).c_str());
    }
  }
  std::printf("[ figures  ] perturbed own-recording runs: %d/%d succeeded\n", ok, cases);
  EXPECT_GE(ok, kMinSuccessRate * cases) << ok << "/" << cases;
}

}  // namespace
}  // namespace srp
