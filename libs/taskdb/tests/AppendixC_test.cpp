// The thesis' Appendix C task model (instruction 1), written through the DAOs
// and read back row by row.
#include <gtest/gtest.h>

#include <sstream>

#include "Backends.h"
#include "TestDb.h"
#include "srp/core/Json.h"
#include "srp/taskdb/GroundedProductDao.h"
#include "srp/taskdb/HandPositionDao.h"
#include "srp/taskdb/ProductDao.h"
#include "srp/taskdb/ProductPoseDao.h"
#include "srp/taskdb/SourceLocationDao.h"
#include "srp/taskdb/TargetLocationDao.h"
#include "srp/taskdb/TaskModelDao.h"
#include "srp/taskdb/TaskModelReport.h"
#include "srp/taskdb/TaskModelStore.h"
#include "srp/taskdb/TaskModelTargetObjectDao.h"

using namespace srp::taskdb;
using srp::taskdb::test::AppendixC;
using srp::taskdb::test::yawQuaternion;

namespace {
constexpr double kExact = 0.0;          // SQLite REAL stores doubles bit for bit
constexpr double kYawTol_rad = 1e-12;   // yaw -> quaternion -> yaw
const std::nullopt_t N = std::nullopt;

// Table C.1 (ObjectId, ObjectName, SourceLocation, TargetLocation, Color, TokenId, SentenceId, ClassId).
const std::vector<ProductRow> kProducts = {
    {0, "cuboid", 0, N, N, 4, 0, 3},         {1, "box", N, N, "blue", 8, 0, 1},
    {2, "cuboid", N, 0, N, 12, 0, 3},        {3, "box", N, N, "gray", 17, 0, 0},
    {4, "star", N, N, N, 5, 1, 5},           {5, "star", 2, N, N, 9, 1, 5},
    {6, "box", N, N, "gray", 18, 1, 0},      {7, "cuboid", N, N, N, 14, 1, 3},
    {8, "parallelogram", N, N, N, 4, 2, 2},  {9, "parallelogram", N, 1, N, 8, 2, 2},
    {10, "star", N, N, N, 11, 2, 5},         {11, "octagon", 4, N, N, 4, 3, 4},
    {12, "box", N, N, "gray", 16, 3, 0},     {13, "parallelogram", N, N, N, 8, 3, 2}};
const std::vector<SourceLocationRow> kSources = {{0, 1, "from"}, {1, 6, "in"}, {2, 7, "next to"}, {3, 12, "in"}, {4, 13, "next to"}};
const std::vector<TargetLocationRow> kTargets = {{0, 3, "in"}, {1, 10, "beside"}};
const std::vector<int> kPlan = {0, 2, 4, 5, 8, 9, 11};
const std::vector<HandPositionRow> kHand = {{1, {1.58, 8.05, 2.31}, true}, {2, {4.76, 2.41, 6.95}, true},
                                            {3, {1.27, 6.44, 1.85}, true}, {4, {3.33, 1.69, 4.86}, true},
                                            {5, {8.73, 4.43, 1.27}, true}};
const std::vector<GroundedProductRow> kGrounded = {{0, "graybox", N, N, "gray"}, {1, "bluebox", N, N, "blue"},
                                                   {2, "parallelogram", N, 1, N}, {3, "cuboid", 0, 0, N},
                                                   {4, "octagon", 4, N, N},       {5, "star", 2, N, N}};
struct PoseLine { int t; double x, y, z, rz; char skill; };
// Table C.7 ProductPoseCuboid: the rows the thesis prints.
const std::vector<PoseLine> kCuboid = {{1, -0.092, -0.017, 0.553, 3, ' '},   {2, -0.092, -0.017, 0.554, 3, ' '},
                                       {96, -0.396, -0.103, 0.58, 0.091, 'R'}, {97, -0.092, -0.017, 0.55, 3, 'R'},
                                       {98, -0.092, -0.017, 0.55, 3, 'R'},   {122, -0.49, -0.128, 0.72, 0, 'G'},
                                       {123, -0.49, -0.128, 0.72, 0, 'M'},   {124, -0.51, -0.134, 0.75, 0, 'M'},
                                       {231, 0.121, -0.008, 0.55, 1.9, 'L'}};

ProductPoseRow poseRow(const PoseLine& l) {
  ProductPoseRow r;
  r.classId = 3;
  r.timeId = l.t;
  r.p_m = {l.x, l.y, l.z};
  r.q = yawQuaternion(l.rz);
  r.reach = l.skill == 'R';
  r.grasp = l.skill == 'G';
  r.move = l.skill == 'M';
  r.release = l.skill == 'L';
  return r;
}

// Writes the Appendix C model through the DAOs, as the thesis' Task Module did.
int writeThroughDaos(TaskDatabase& db) {
  ScopedTransaction tx(db);
  TaskModelInfo info;
  info.name = "appendix-c";
  info.instruction = "Begin by picking up the cuboid from the blue box and placing it in the gray box. ...";
  const int id = TaskModelDao(db).add(info);
  for (const auto& r : kProducts) ProductDao(db).add(id, r);
  for (const auto& r : kSources) SourceLocationDao(db).add(id, r);
  for (const auto& r : kTargets) TargetLocationDao(db).add(id, r);
  for (std::size_t i = 0; i < kPlan.size(); ++i) TaskModelTargetObjectDao(db).add(id, static_cast<int>(i), kPlan[i]);
  for (const auto& r : kGrounded) GroundedProductDao(db).add(id, r);
  HandPositionDao(db).addMany(id, kHand);
  for (const auto& l : kCuboid) ProductPoseDao(db).add(id, poseRow(l));
  tx.commit();
  return id;
}
}  // namespace

TEST_P(AppendixC, EveryRowReadsBackThroughTheDaos) {
  auto db = TaskDatabase::open(newDatabase("appendix_c"));
  const int id = writeThroughDaos(db);
  EXPECT_EQ(id, 1);  // the thesis' TaskModelId

  const auto products = ProductDao(db).list(id);
  ASSERT_EQ(products.size(), kProducts.size());
  for (std::size_t i = 0; i < kProducts.size(); ++i) EXPECT_EQ(products[i], kProducts[i]) << "Products row " << i;
  EXPECT_EQ(SourceLocationDao(db).list(id), kSources);
  EXPECT_EQ(TargetLocationDao(db).list(id), kTargets);
  EXPECT_EQ(TaskModelTargetObjectDao(db).list(id), kPlan);
  EXPECT_EQ(GroundedProductDao(db).list(id), kGrounded);
  const auto hand = HandPositionDao(db).list(id);
  ASSERT_EQ(hand.size(), kHand.size());
  for (std::size_t i = 0; i < kHand.size(); ++i) {
    EXPECT_EQ(hand[i].timeId, kHand[i].timeId);
    EXPECT_NEAR((hand[i].p_m - kHand[i].p_m).norm(), 0.0, kExact) << "HandPositions row " << i;
  }
  const auto poses = ProductPoseDao(db).list(id);
  ASSERT_EQ(poses.size(), kCuboid.size());
  for (std::size_t i = 0; i < kCuboid.size(); ++i) {
    const auto& l = kCuboid[i];
    EXPECT_EQ(poses[i].timeId, l.t);
    EXPECT_NEAR((poses[i].p_m - Eigen::Vector3d(l.x, l.y, l.z)).norm(), 0.0, kExact) << "TimeId " << l.t;
    EXPECT_NEAR(poses[i].yaw_rad(), l.rz, kYawTol_rad) << "TimeId " << l.t;
    EXPECT_EQ(poses[i].reach, l.skill == 'R');
    EXPECT_EQ(poses[i].grasp, l.skill == 'G');
    EXPECT_EQ(poses[i].move, l.skill == 'M');
    EXPECT_EQ(poses[i].release, l.skill == 'L');
  }

  // The planner's queries.
  const auto ordered = TaskModelTargetObjectDao(db).orderedTargetObjects(id);
  ASSERT_EQ(ordered.size(), 7u);
  EXPECT_EQ(ordered.front().objectName, "cuboid");
  EXPECT_EQ(ordered.back().objectName, "octagon");
  const auto frames = ProductPoseDao(db).graspReleaseFrames(id, 3);
  EXPECT_EQ(frames.graspTimeId, 122);
  EXPECT_EQ(frames.releaseTimeId, 231);
  EXPECT_EQ(ProductPoseDao(db).inFrameRange(id, 3, 96, 123).size(), 5u);
  EXPECT_EQ(HandPositionDao(db).inFrameRange(id, 2, 4).size(), 3u);
  EXPECT_FALSE(ProductPoseDao(db).graspReleaseFrames(id, 5).graspTimeId.has_value());
}

TEST_P(AppendixC, BundledExampleIsTheSameModelAndReportsTheFourSteps) {
  auto db = TaskDatabase::open(newDatabase("appendix_c_json"));
  const int viaDaos = writeThroughDaos(db);
  const TaskModel example = taskModelFromJson(
      srp::core::readJsonFile(std::string(SRP_DATASETS_DIR) + "/examples/appendix_c_instruction1.json"), "example");
  TaskModelStore store(db);
  const int viaJson = store.write(example);
  const TaskModel a = store.read(viaDaos), b = store.read(viaJson);
  EXPECT_EQ(a.products, b.products);
  EXPECT_EQ(a.sourceLocations, b.sourceLocations);
  EXPECT_EQ(a.targetLocations, b.targetLocations);
  EXPECT_EQ(a.targetObjectIds, b.targetObjectIds);
  EXPECT_EQ(a.groundedProducts, b.groundedProducts);
  ASSERT_EQ(a.productPoses.size(), b.productPoses.size());
  for (std::size_t i = 0; i < a.productPoses.size(); ++i)
    EXPECT_NEAR(a.productPoses[i].yaw_rad(), b.productPoses[i].yaw_rad(), kYawTol_rad);
  EXPECT_EQ(b.info.version, 2);  // same name written twice: a new version

  const auto steps = planSteps(b);
  ASSERT_EQ(steps.size(), 4u);
  EXPECT_EQ(steps[0].objectName, "cuboid");
  EXPECT_EQ(steps[0].sources, std::vector<std::string>{"from blue box"});
  EXPECT_EQ(steps[0].targets, std::vector<std::string>{"in gray box"});
  EXPECT_EQ(steps[2].targets, std::vector<std::string>{"beside star"});
  std::ostringstream appendix;
  writeAppendixC(b, appendix);
  EXPECT_NE(appendix.str().find("Table C.7: ProductPoseCuboid"), std::string::npos);
  EXPECT_NE(appendix.str().find("231\t2\t0.121\t-0.008\t0.55\t1.9\t\t\t\t1"), std::string::npos) << appendix.str();
  EXPECT_NE(appendix.str().find("0\tcuboid\t0\t\t\t4\t0\t3"), std::string::npos);
}
