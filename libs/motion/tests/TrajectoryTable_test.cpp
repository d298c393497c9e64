#include "srp/motion/TrajectoryTable.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "srp/core/Error.h"
#include "srp/motion/SyntheticPickPlace.h"

namespace srp::motion {
namespace {

std::string tempPath(const std::string& name) { return std::string(SRP_BINARY_DIR) + "/motion_test_" + name; }

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(TrajectoryTable, RoundTripsASyntheticDemoAndSegmentsTheSame) {
  const auto demo = motion::SyntheticPickPlaceGenerator().generate();
  TrajectoryTable table{demo.hand, demo.objects};
  const std::string path = tempPath("roundtrip.csv");
  table.writeCsv(path);
  const TrajectoryTable back = TrajectoryTable::readCsv(path, 30.0);
  ASSERT_EQ(back.hand.size(), demo.hand.size());
  ASSERT_EQ(back.objects.size(), demo.objects.size());
  for (std::size_t i = 0; i < demo.hand.size(); ++i) {
    EXPECT_EQ(back.hand[i].valid, demo.hand[i].valid);
    if (demo.hand[i].valid) EXPECT_TRUE(back.hand[i].p_m == demo.hand[i].p_m);
  }
  const auto a = Segmenter().segment(demo.hand, demo.objects, demo.planOrder);
  const auto b = Segmenter().segment(back.hand, back.objects, demo.planOrder);
  for (std::size_t k = 0; k < a.objects.size(); ++k) {
    EXPECT_EQ(a.objects[k].graspFrame, b.objects[k].graspFrame);
    EXPECT_EQ(a.objects[k].releaseFrame, b.objects[k].releaseFrame);
  }
  std::remove(path.c_str());
}

TEST(TrajectoryTable, RejectsBadFilesNamingTheProblem) {
  EXPECT_THROW(TrajectoryTable::readCsv(tempPath("missing.csv")), core::FileError);
  const std::string path = tempPath("bad.csv");
  const std::string header = "frame,hand_x,hand_y,hand_z,star_x,star_y,star_z,star_rz\n";
  writeText(path, "frame,hand_x,hand_y\n0,1,2\n");
  EXPECT_THROW(TrajectoryTable::readCsv(path), core::InvalidInputError);
  writeText(path, header + "0,0.1,0.2,0.3,0.1,0.1,0.9,0\n1,0.1,nan,0.3,0.1,0.1,0.9,0\n");
  try {
    TrajectoryTable::readCsv(path);
    FAIL() << "NaN accepted";
  } catch (const core::InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hand_y"), std::string::npos) << e.what();
  }
  writeText(path, header + "0,0.1,0.2,0.3,0.1,0.1,0.9,0\n");
  EXPECT_THROW(TrajectoryTable::readCsv(path), core::InvalidInputError);  // single sample
  writeText(path, header + "0,0.1,0.2,0.3,0.1,0.1,0.9,0\n0,0.1,0.2,0.3,0.1,0.1,0.9,0\n");
  EXPECT_THROW(TrajectoryTable::readCsv(path), core::InvalidInputError);  // frame not increasing
  writeText(path, header + "0,0.1,0.2,0.3,0.1,0.1,0.9\n1,0.1,0.2,0.3,0.1,0.1,0.9,0\n");
  EXPECT_THROW(TrajectoryTable::readCsv(path), core::InvalidInputError);  // short row
  std::remove(path.c_str());
}

}  // namespace
}  // namespace srp::motion
