#include "srp/perception/TagBoard.h"

#include <gtest/gtest.h>

#include "RealData.h"
#include "srp/perception/RgbdFolder.h"

namespace srp::perception {
namespace {

constexpr double kBoardPositionTol_m = 5e-3;   // issue 5 acceptance
constexpr double kBoardAngleTol_rad = 1.0 * M_PI / 180.0;

TEST(TagBoard, GridLayoutPlacesTagsOnAGrid) {
  const TagBoardLayout layout = TagBoardLayout::vispRbtBoard();
  ASSERT_EQ(layout.X_board_tag.size(), 12u);
  EXPECT_NEAR(layout.X_board_tag.at(0).translation().x(), 0.0955 / 2, 1e-12);
  EXPECT_NEAR(layout.X_board_tag.at(5).translation().x(), 1.25 * 0.0955 + 0.0955 / 2, 1e-12);
  EXPECT_NEAR(layout.X_board_tag.at(5).translation().y(), 1.25 * 0.0955 + 0.0955 / 2, 1e-12);
  EXPECT_NEAR(layout.X_board_tag.at(11).translation().x(), 2.5 * 0.0955 + 0.0955 / 2, 1e-12);
}

TEST(TagBoard, NoBoardTagGivesNullopt) {
  EXPECT_FALSE(estimateBoardPose({}, TagBoardLayout::vispRbtBoard(), {600, 600, 320, 240, 640, 480}).has_value());
}

// Acceptance (issue 5): the board pose within 5 mm and 1 deg of the stored
// poses in every frame of the real RealSense recording.
TEST(TagBoard, RealRecordingMatchesStoredBoardPoses) {
  const auto frames = readRgbdFolder(testing::rbtFolder());
  const auto stored = testing::storedBoardPoses();
  ASSERT_EQ(frames.size(), 50u);
  ASSERT_EQ(stored.size(), frames.size());
  AprilTagDetector detector({0.0955});
  const TagBoardLayout layout = TagBoardLayout::vispRbtBoard();
  double worstPos_m = 0.0, worstAngle_rad = 0.0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const auto tags = detector.detect(frames[i].colour_bgr8, frames[i].intrinsics);
    const auto board = estimateBoardPose(tags, layout, frames[i].intrinsics);
    ASSERT_TRUE(board.has_value()) << "frame " << i;
    EXPECT_GE(board->tagsUsed, 6) << "frame " << i;
    EXPECT_LT(board->rmsReprojection_px, 1.5) << "frame " << i;
    const double dp = core::translationDistance(board->X_camera_board, stored[i]);
    const double da = core::rotationAngleBetween(board->X_camera_board.linear(), stored[i].linear());
    EXPECT_LT(dp, kBoardPositionTol_m) << "frame " << i;
    EXPECT_LT(da, kBoardAngleTol_rad) << "frame " << i;
    worstPos_m = std::max(worstPos_m, dp);
    worstAngle_rad = std::max(worstAngle_rad, da);
  }
  std::printf("[ figures  ] board vs stored, worst of %zu frames: %.2f mm, %.3f deg\n", frames.size(), worstPos_m * 1e3,
              worstAngle_rad * 180 / M_PI);
}

}  // namespace
}  // namespace srp::perception
