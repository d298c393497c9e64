// What perception saw, drawn: outlines where the model projects, the palm where
// the hand is, carried-forward poses grey, and a contact sheet of tiles.
#include "srp/perception/PerceptionDrawing.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "srp/core/ObjectCatalogue.h"
#include "srp/kb/KnowledgeBase.h"

using namespace srp;

namespace {
constexpr int kOutlineTol_px = 2;  // anti-aliased lines: the outline within 2 px of the projected corners

perception::PerceptionResult oneCuboid(bool detected) {
  perception::PerceptionResult r;
  r.intrinsics = {300.0, 300.0, 159.5, 119.5, 320, 240};
  r.frames = 1;
  core::Pose3 X = core::Pose3::Identity();
  X.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();  // object z towards the camera
  X.translation() = Eigen::Vector3d(0.0, 0.0, 0.6);
  perception::ObjectTrajectory t;
  t.className = "cuboid";
  t.samples.push_back({0, 0.0, X, detected, 0.87});
  r.objects.push_back(t);
  r.hand.append({0, 0.0, Eigen::Vector3d(0.06, 0.05, 0.5), true});
  r.handDetected = 1;
  core::Pose3 X_camera_table = X;  // the table frame's axes away from the cuboid
  X_camera_table.translation() = Eigen::Vector3d(-0.15, 0.08, 0.6);
  r.X_camera_table = X_camera_table;
  return r;
}

int pixelsNear(const cv::Mat& img, cv::Point p, int radius, const std::function<bool(const cv::Vec3b&)>& is) {
  int n = 0;
  for (int y = p.y - radius; y <= p.y + radius; ++y)
    for (int x = p.x - radius; x <= p.x + radius; ++x)
      if (x >= 0 && y >= 0 && x < img.cols && y < img.rows && is(img.at<cv::Vec3b>(y, x))) ++n;
  return n;
}
}  // namespace

TEST(PerceptionDrawing, OutlineAtTheProjectedModelAndThePalmAtTheHand) {
  const auto kb = kb::loadCatalogue(core::ObjectCatalogue::defaultPath());
  const auto& cuboid = kb.at("cuboid");
  const perception::PerceptionResult seen = oneCuboid(true);
  cv::Mat img(240, 320, CV_8UC3, cv::Scalar::all(0));
  perception::PerceptionDrawing(seen, kb).draw(img, 0);
  // The cuboid's top face corner (x, y = +-half, z = height) projects here; its colour is there.
  const Eigen::Vector3d corner_camera = seen.objects[0].samples[0].X_camera_object *
                                        Eigen::Vector3d(cuboid.dimensions_m.x() / 2, cuboid.dimensions_m.y() / 2,
                                                        cuboid.dimensions_m.z());
  const auto uv = seen.intrinsics.project(corner_camera);
  ASSERT_TRUE(uv.has_value());
  const cv::Vec3b red(static_cast<uchar>(cuboid.rgb.z() * 255), static_cast<uchar>(cuboid.rgb.y() * 255),
                      static_cast<uchar>(cuboid.rgb.x() * 255));
  const auto isRed = [&](const cv::Vec3b& c) { return cv::norm(cv::Vec3i(c) - cv::Vec3i(red)) < 40; };
  EXPECT_GT(pixelsNear(img, cv::Point(cvRound(uv->x()), cvRound(uv->y())), kOutlineTol_px, isRed), 0);
  EXPECT_EQ(pixelsNear(img, cv::Point(160, 120), 2, isRed), 0) << "an outline, not a filled shape";
  // The palm: a white disc where the hand projects (u = 300 * 0.06 / 0.5 + 159.5 = 195.5).
  const auto isWhite = [](const cv::Vec3b& c) { return c[0] > 240 && c[1] > 240 && c[2] > 240; };
  EXPECT_GT(pixelsNear(img, cv::Point(196, 150), 2, isWhite), 10);
  // A pose carried from another frame is drawn grey, not in the class' colour.
  cv::Mat kept(240, 320, CV_8UC3, cv::Scalar::all(0));
  perception::PerceptionDrawing(oneCuboid(false), kb).draw(kept, 0);
  EXPECT_EQ(pixelsNear(kept, cv::Point(cvRound(uv->x()), cvRound(uv->y())), kOutlineTol_px, isRed), 0);
}

TEST(PerceptionDrawing, ContactSheetHoldsEveryTileWithItsFrame) {
  const std::vector<int> frames = perception::contactSheetFrames(100, 5, {42, 42, 150});
  EXPECT_EQ(frames, (std::vector<int>{0, 25, 42, 50, 74, 99})) << "spread, the marked frame once, none beyond";
  std::vector<perception::ContactSheetTile> tiles(6);
  for (auto& t : tiles) t.image = cv::Mat(240, 320, CV_8UC3, cv::Scalar(0, 255, 0));
  tiles[2].border = cv::Scalar(40, 40, 255);
  tiles[2].flag = "LOW CONFIDENCE";
  const cv::Mat sheet = perception::composeContactSheet(tiles, "test", 4, 200);
  ASSERT_EQ(sheet.type(), CV_8UC3);
  // 4 columns of 200 px tiles, 2 rows of 150 px tiles.
  EXPECT_GT(sheet.cols, 4 * 200);
  EXPECT_GT(sheet.rows, 2 * 150);
  int green = 0;
  for (int y = 0; y < sheet.rows; ++y)
    for (int x = 0; x < sheet.cols; ++x) green += sheet.at<cv::Vec3b>(y, x) == cv::Vec3b(0, 255, 0);
  EXPECT_GT(green, 6 * 200 * 150 * 8 / 10) << "six tiles' pixels (less captions and flags)";
}
