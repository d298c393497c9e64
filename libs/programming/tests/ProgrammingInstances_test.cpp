// Several parts of one class: `programTask` with the demo's scene perceives
// each cuboid instance, grounds "the red/blue cuboid" to the instance the
// colour names (SceneGrounder on the perceived scene) and stores its
// InstanceId in Products, GroundedProducts, ProductPose and Skills. Data: a
// synthetic duplicate-parts demos (srp::synth::makeDuplicatePartsDemo, seeds
// 1-5, 320x240, default sensor noise) rendered into a temporary folder.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <fstream>

#include "srp/core/Error.h"
#include "srp/core/Scene.h"
#include "srp/execution/SceneGrounder.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/programming/MotionRows.h"
#include "srp/programming/ProgrammingPipeline.h"
#include "srp/programming/ProgrammingStages.h"
#include "srp/synth/DemoGenerator.h"
#include "srp/synth/DuplicatePartsDemo.h"
#include "srp/taskdb/TaskModelStore.h"
#include "SmallDemoOptions.h"

using namespace srp;

namespace {
constexpr std::uint32_t kSeeds = 5;
// Grasp/release against the truth as the segmentation is judged on its own
// data: most events within +-3 frames, none beyond +-5 (its worst on the
// real-track report seeds is 4-5). The rendered palm creeps ~2 mm toward the
// part for ~0.25 s after the grip opens, and the release is placed where the
// hand comes closest to the final place (what real placements show), so a
// rendered release can come up to 4 frames late.
constexpr int kEventTol_frames = 3;
constexpr int kEventWorst_frames = 5;
constexpr int kMaxEventsOutsideTol = 1;  // of the 10 events of seeds 1-5

struct Demo {
  synth::DuplicatePartsDemo scene;
  std::string rawlog, scenePath;
  synth::DemoGroundTruth gt;
};

const Demo& demo(std::uint32_t kSeed = 3) {
  static std::map<std::uint32_t, Demo> demos;
  if (const auto it = demos.find(kSeed); it != demos.end()) return it->second;
  const Demo d = [kSeed] {
    const auto dir = std::filesystem::temp_directory_path() / ("srp_programming_instances_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    const core::Scene base = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
    const auto kb = kb::loadCatalogue(base.cataloguePath);
    Demo out;
    out.scene = synth::makeDuplicatePartsDemo(base, kb, kSeed);
    out.scenePath = (dir / ("scene_" + std::to_string(kSeed) + ".json")).string();
    std::ofstream(out.scenePath) << out.scene.scene.toJson().dump(1);
    const synth::SynthDemoOptions opt = programming::test::smallDemoOptions(kSeed);
    out.rawlog = (dir / ("duplicates_" + std::to_string(kSeed) + ".rawlog")).string();
    const auto r = synth::generateSyntheticDemo(out.scene.scene, kb, out.scene.plan, opt, out.rawlog);
    out.gt = synth::DemoGroundTruth::load(r.groundTruthPath);
    return out;
  }();
  return demos.emplace(kSeed, d).first->second;
}

programming::ProgrammingOptions options(const std::string& instruction, const std::string& dbName,
                                        const Demo& d = demo()) {
  const auto dir = std::filesystem::path(d.rawlog).parent_path();
  programming::ProgrammingOptions o;
  o.instruction = instruction;
  o.demoPath = d.rawlog;
  o.scenePath = d.scenePath;
  o.dbPath = (dir / dbName).string();
  for (const char* s : {"", "-wal", "-shm"}) std::filesystem::remove(o.dbPath + s);
  o.name = "duplicates";
  return o;
}

// The moved instance's ProductPose rows have one grasp frame; the other instance's no skill flag.
void expectFlagsOnTheMovedInstanceOnly(const taskdb::TaskModel& m, const Demo& d) {
  int movedGrasps = 0, otherFlags = 0;
  for (const auto& p : m.productPoses) {
    if (p.instanceId == d.scene.movedId) movedGrasps += p.grasp;
    if (p.instanceId == d.scene.otherId) otherFlags += p.reach || p.grasp || p.move || p.release;
  }
  EXPECT_EQ(movedGrasps, 1);
  EXPECT_EQ(otherFlags, 0);
}

// One seed: "the <colour> cuboid" -> the moved instance, in every table.
// Adds to `outside` how many of its two events are outside kEventTol_frames.
void expectInstanceStored(std::uint32_t seed, int& outside) {
  const Demo& d = demo(seed);
  const auto o = options(d.scene.plan.at("instruction").get<std::string>(), "colour.db", d);
  const programming::ProgramResult r = programming::programTask(o);
  ASSERT_EQ(r.objects.size(), 1u);
  EXPECT_EQ(r.objects[0].name, "cuboid");
  EXPECT_EQ(r.objects[0].instanceId, d.scene.movedId);
  EXPECT_TRUE(r.objects[0].moved);
  const auto* event = d.gt.eventFor(d.scene.movedId);
  ASSERT_NE(event, nullptr);
  EXPECT_NEAR(r.objects[0].graspFrame, event->graspFrame, kEventWorst_frames);
  EXPECT_NEAR(r.objects[0].releaseFrame, event->releaseFrame, kEventWorst_frames);
  outside += (std::abs(r.objects[0].graspFrame - event->graspFrame) > kEventTol_frames) +
                      (std::abs(r.objects[0].releaseFrame - event->releaseFrame) > kEventTol_frames);

  auto db = taskdb::TaskDatabase::open(o.dbPath);
  const taskdb::TaskModel m = taskdb::TaskModelStore(db).read(r.taskModelId);
  // The phrase "the <colour> cuboid" names the moved instance.
  int cuboidProducts = 0;
  for (const auto& p : m.products)
    if (p.objectName == "cuboid") {
      ++cuboidProducts;
      EXPECT_EQ(p.instanceId, d.scene.movedId);
    } else {
      EXPECT_EQ(p.instanceId, "") << p.objectName << ": a class with one instance";
    }
  EXPECT_EQ(cuboidProducts, 1);
  // Both instances were seen and stored, each with its colour word.
  std::set<std::string> grounded;
  for (const auto& g : m.groundedProducts)
    if (g.objectName == "cuboid") {
      grounded.insert(g.instanceId);
      ASSERT_TRUE(g.colour.has_value());
      EXPECT_EQ(*g.colour, d.scene.scene.findObject(g.instanceId)->colour);
    }
  EXPECT_EQ(grounded, (std::set<std::string>{d.scene.movedId, d.scene.otherId}));
  // The skills are the moved instance's; its grasp row is flagged, the other's never.
  EXPECT_EQ(m.skills.size(), 4u);
  for (const auto& s : m.skills) EXPECT_EQ(s.instanceId, d.scene.movedId);
  expectFlagsOnTheMovedInstanceOnly(m, d);
  std::printf("[ figures  ] seed %u: '%s' -> %s, grasp %d (truth %d), release %d (truth %d)\n", seed,
              o.instruction.c_str(), r.objects[0].instanceId.c_str(), r.objects[0].graspFrame, event->graspFrame,
              r.objects[0].releaseFrame, event->releaseFrame);
}

TEST(ProgrammingInstances, StoresTheInstanceTheColourNames) {
  int outside = 0;
  for (std::uint32_t seed = 1; seed <= kSeeds; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    expectInstanceStored(seed, outside);
  }
  EXPECT_LE(outside, kMaxEventsOutsideTol) << "events outside +-" << kEventTol_frames << " frames";
}

// Grounding is the scene grounder's, not a colour lookup: "the leftmost /
// rightmost cuboid" (the demonstrator's view = the camera's image axes on the
// table) names the moved instance, read in the perceived scene.
TEST(ProgrammingInstances, GroundsASuperlativeInThePerceivedScene) {
  const Demo& d = demo(2);
  const core::Pose3 X_camera_world = d.gt.X_world_camera.inverse();
  const auto& first = d.gt.frames.front().X_world_objects;
  const double movedX = (X_camera_world * first.at(d.scene.movedId)).translation().x();
  const double otherX = (X_camera_world * first.at(d.scene.otherId)).translation().x();
  const std::string word = movedX < otherX ? "leftmost" : "rightmost";
  const auto o = options("Pick up the " + word + " cuboid and place it in the gray box.", "superlative.db", d);
  const programming::ProgramResult r = programming::programTask(o);
  ASSERT_EQ(r.objects.size(), 1u);
  EXPECT_EQ(r.objects[0].instanceId, d.scene.movedId) << word;
  EXPECT_TRUE(r.objects[0].moved);
  auto db = taskdb::TaskDatabase::open(o.dbPath);
  const taskdb::TaskModel m = taskdb::TaskModelStore(db).read(r.taskModelId);
  for (const auto& p : m.products)
    if (p.objectName == "cuboid") EXPECT_EQ(p.instanceId, d.scene.movedId);
}

// No scene file: "the blue cuboid" (the catalogue's cuboid is red) is looked
// for in blue, so the demo's moved blue cuboid is learned, not the red one
// that stays (seed 1 moves the blue one). Its one instance: InstanceId "".
TEST(ProgrammingInstances, WithoutASceneTheInstructionsColourIsLookedFor) {
  const Demo& d = demo(1);
  ASSERT_EQ(d.scene.scene.findObject(d.scene.movedId)->colour, "blue");
  auto o = options("Pick up the blue cuboid and place it in the gray box.", "noscene.db", d);
  o.scenePath.clear();
  const programming::ProgramResult r = programming::programTask(o);
  ASSERT_EQ(r.objects.size(), 1u);
  EXPECT_EQ(r.objects[0].instanceId, "");
  EXPECT_TRUE(r.objects[0].moved);
  const auto* event = d.gt.eventFor(d.scene.movedId);
  ASSERT_NE(event, nullptr);
  EXPECT_NEAR(r.objects[0].graspFrame, event->graspFrame, kEventTol_frames);
  EXPECT_NEAR(r.objects[0].releaseFrame, event->releaseFrame, kEventWorst_frames);
}

// No scene file, two colours of one part class named: two instances.
TEST(ProgrammingInstances, InstructionNamingTwoColoursOfAPartGivesTwoInstances) {
  const auto kb = kb::loadCatalogue(core::ObjectCatalogue::defaultPath());
  const auto grounded = programming::groundPlan(
      programming::parsePlan("Pick up the red cuboid and place it in the gray box. Then pick up the blue cuboid and "
                             "place it in the blue box."),
      kb);
  const auto scene = programming::instructionInstances(grounded, kb);
  ASSERT_TRUE(scene.has_value());
  std::set<std::string> ids;
  for (const auto& o : scene->objects) {
    ids.insert(o.id);
    EXPECT_EQ(o.className, "cuboid");
    EXPECT_EQ(o.id, "cuboid_" + o.colour);
  }
  EXPECT_EQ(ids, (std::set<std::string>{"cuboid_blue", "cuboid_red"}));
  // One colour, or none: no instances.
  EXPECT_FALSE(programming::instructionInstances(
                   programming::groundPlan(programming::parsePlan("Put the blue cuboid in the gray box."), kb), kb)
                   .has_value());
}

// `srp motion` re-learning from the stored rows (motionInputsFromTaskModel,
// motion::learnSkills, storeSkills, as cmd_motion does) on a task model that
// holds two instances of the moved class: each instance's rows are its own
// track, the moved instance gets back exactly the skills programming stored
// (none lost, none added under InstanceId ""), the other instance none.
TEST(ProgrammingInstances, SrpMotionRelearnsEachInstancesOwnSkills) {
  for (std::uint32_t seed : {1u, 2u}) {  // seed 1 moves the blue cuboid, seed 2 the red one
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Demo& d = demo(seed);
    const auto o = options(d.scene.plan.at("instruction").get<std::string>(), "relearn.db", d);
    const programming::ProgramResult r = programming::programTask(o);
    auto db = taskdb::TaskDatabase::open(o.dbPath);
    taskdb::TaskModelStore store(db);
    const taskdb::TaskModel programmed = store.read(r.taskModelId);
    ASSERT_EQ(programmed.skills.size(), 4u);

    const programming::MotionInputs inputs = programming::motionInputsFromTaskModel(programmed);
    ASSERT_EQ(inputs.planOrder, std::vector<std::string>{d.scene.movedId});
    const motion::LearnedSkills learned = motion::learnSkills(inputs);
    ASSERT_EQ(learned.skills.size(), 1u);
    EXPECT_EQ(learned.skills[0].objectName, d.scene.movedId);
    programming::storeSkills(db, r.taskModelId, learned.skills, inputs);

    const taskdb::TaskModel relearned = store.read(r.taskModelId);
    EXPECT_EQ(relearned.skills, programmed.skills);  // the same rows: the moved instance's, none lost or added
    EXPECT_EQ(relearned.productPoses, programmed.productPoses);  // the same flags
    expectFlagsOnTheMovedInstanceOnly(relearned, d);
  }
}

TEST(ProgrammingInstances, AnAmbiguousPhraseNamesTheCandidatesAndStoresNothing) {
  const auto o = options("Pick up the cuboid and place it in the gray box.", "ambiguous.db");
  try {
    programming::programTask(o);
    FAIL() << "'the cuboid' fits two instances";
  } catch (const execution::GroundingError& e) {
    EXPECT_EQ(e.candidates().size(), 2u) << e.what();
    EXPECT_NE(std::string(e.what()).find("say which"), std::string::npos) << e.what();
  }
  auto db = taskdb::TaskDatabase::open(o.dbPath);
  EXPECT_TRUE(taskdb::TaskModelStore(db).list().empty());
}

}  // namespace
