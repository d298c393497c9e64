#include "srp/programming/MotionRows.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "srp/core/Error.h"
#include "srp/motion/SkillLearner.h"
#include "srp/motion/SyntheticPickPlace.h"
#include "srp/taskdb/ProductPoseDao.h"
#include "srp/taskdb/TaskModelStore.h"

namespace srp::programming {
namespace {

constexpr int kFrameTol = 3;

std::string tempPath(const std::string& name) { return std::string(SRP_BINARY_DIR) + "/programming_test_motion_rows_" + name; }

void removeDb(const std::string& path) {
  for (const char* suffix : {"", "-wal", "-shm"}) std::remove((path + suffix).c_str());
}

TEST(MotionRows, StoredDemoSegmentsLearnsAndStoresSkillsThatRollOutIdentically) {
  const auto demo = motion::SyntheticPickPlaceGenerator().generate();
  const std::string path = tempPath("mapping.db");
  removeDb(path);
  auto db = taskdb::TaskDatabase::open(path);
  taskdb::TaskModelStore store(db);
  const int id = store.write(taskModelFromTracks(demo, "synthetic", demo.instruction()));
  const taskdb::TaskModel model = store.read(id);

  const MotionInputs in = motionInputsFromTaskModel(model);
  ASSERT_EQ(in.planOrder, demo.planOrder);
  ASSERT_EQ(in.hand.size(), demo.hand.size());
  motion::Segmenter::Options thesis;  // the generator's truth is the thesis' grasp definition (mid-hold)
  thesis.events = motion::Segmenter::EventEstimator::Thesis;
  const motion::LearnedSkills learned = motion::learnSkills(in, motion::Segmenter(thesis));
  const auto& seg = learned.segmentation;
  const auto& skills = learned.skills;
  for (std::size_t i = 0; i < seg.objects.size(); ++i) {
    EXPECT_LE(std::abs(seg.objects[i].graspIndex - demo.graspIndex[i]), kFrameTol);
    EXPECT_LE(std::abs(seg.objects[i].releaseIndex - demo.releaseIndex[i]), kFrameTol);
  }
  const auto rows = skillRows(skills, in);
  ASSERT_EQ(rows.size(), 16u);
  storeSkills(db, id, skills, in);
  // The ProductPose flags mark the grasp and release frames.
  for (const auto& s : skills) {
    const MotionInputs::RowKey& key = in.rowKeyByName.at(s.objectName);
    const auto frames = taskdb::ProductPoseDao(db).graspReleaseFrames(id, key.classId, key.instanceId);
    EXPECT_EQ(frames.graspTimeId, s.graspFrame);
    EXPECT_EQ(frames.releaseTimeId, s.releaseFrame);
  }
  EXPECT_THROW(storeSkills(db, id + 100, skills, in), core::InvalidInputError);

  const taskdb::TaskModel back = store.read(id);
  ASSERT_EQ(back.skills.size(), 16u);
  int moves = 0;
  for (const auto& row : back.skills) {
    if (row.skill != core::SkillType::Move) continue;
    const auto& s = skills[static_cast<std::size_t>(moves++)];
    EXPECT_EQ(row.startTimeId, in.hand[s.graspIndex].frame);
    EXPECT_EQ(row.endTimeId, in.hand[s.releaseIndex].frame);
    const motion::Dmp stored = motion::Dmp::fromJson(row.parameters.at("dmp"));
    EXPECT_TRUE(stored.rollout(0.01).y == s.move->rollout(0.01).y) << s.objectName;
  }
  EXPECT_EQ(moves, 4);
  removeDb(path);
}

TEST(MotionRows, PlanObjectWithoutPosesIsAnErrorAndNothingIsStored) {
  const auto demo = motion::SyntheticPickPlaceGenerator().generate();
  taskdb::TaskModel model = taskModelFromTracks(demo, "broken", demo.instruction());
  // The star has no ProductPose rows.
  std::vector<taskdb::ProductPoseRow> kept;
  for (const auto& r : model.productPoses)
    if (r.classId != 1) kept.push_back(r);
  model.productPoses = kept;
  const MotionInputs in = motionInputsFromTaskModel(model);
  EXPECT_THROW(motion::Segmenter().segment(in.hand, in.objects, in.planOrder), core::InvalidInputError);

  taskdb::TaskModel ungrounded = taskModelFromTracks(demo, "ungrounded", demo.instruction());
  ungrounded.products[2].classId.reset();
  EXPECT_THROW(motionInputsFromTaskModel(ungrounded), core::InvalidInputError);
}

// End-to-end: the `srp motion` command on a stored synthetic demo (skipped
// when the srp executable has not been built).
TEST(MotionRows, SrpMotionCommandStoresSkillsAndWritesPlots) {
  const std::string srp = std::string(SRP_BINARY_DIR) + "/apps/srp";
  if (!std::filesystem::exists(srp)) FAIL() << srp << " missing: build the srp target (make build) before this test";
  const auto demo = motion::SyntheticPickPlaceGenerator().generate();
  const std::string path = tempPath("cmd.db"), outDir = tempPath("cmd_plots");
  removeDb(path);
  std::filesystem::remove_all(outDir);
  int id = 0;
  {
    auto db = taskdb::TaskDatabase::open(path);
    id = taskdb::TaskModelStore(db).write(taskModelFromTracks(demo, "synthetic", demo.instruction()));
  }
  const std::string cmd = srp + " motion " + std::to_string(id) + " --db " + path + " --out-dir " + outDir + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  {
    auto db = taskdb::TaskDatabase::open(path, taskdb::TaskDatabase::Mode::ReadOnly);
    EXPECT_EQ(taskdb::TaskModelStore(db).read(id).skills.size(), 16u);
  }
  for (const auto& name : demo.planOrder) {
    const std::string png = outDir + "/" + name + ".png";
    ASSERT_TRUE(std::filesystem::exists(png)) << png;
    EXPECT_GT(std::filesystem::file_size(png), 10000u);
  }
  // A missing task model: non-zero exit.
  EXPECT_NE(std::system((srp + " motion 999 --db " + path + " > /dev/null 2>&1").c_str()), 0);
  removeDb(path);
  std::filesystem::remove_all(outDir);
}

}  // namespace
}  // namespace srp::programming
