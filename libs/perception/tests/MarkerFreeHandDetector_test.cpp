// MarkerFreeHandDetector: unit tests on drawn frames (a sleeved arm of boxes
// to scale, seen from above), then issue 5's figures on a rendered synthetic
// demo with ground truth (srp::synth, default scene, thesis instruction 1,
// default sensor noise): the first frames, through the first grasp and lift.
// No tag is used: the detector never decodes one.
//
// SRP_HAND_DEMO=<demo.rawlog> evaluates that demo instead (e.g. the whole
// `srp synth-demo` output, its .gt.json next to it; rendered whole first when
// missing, with seed SRP_HAND_SEED or the scene's); SRP_HAND_DEBUG_DIR=<dir>
// writes every hand frame with the found geometry and a CSV of the palm's
// offset from the found wrist.
#include <gtest/gtest.h>

#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "HandEvaluation.h"
#include "Hrt1Palms.h"
#include "srp/core/Error.h"
#include "srp/core/Json.h"
#include "srp/kb/KnowledgeBase.h"
#include "srp/perception/RgbdFolder.h"
#include "srp/core/Scene.h"
#include "srp/synth/PickPlacePlan.h"

namespace srp::perception {
namespace {

// ---- drawn frames -------------------------------------------------------
// 640x480, fx = fy = 600 px, table 0.85 m away; the hand's back 0.75 m away
// (800 px per metre), the sleeve 1 cm higher. Lengths along the arm from the
// palm centre [m], as a real forearm and hand (and srp::synth's HandModel).
constexpr double kTable_m = 0.85, kHandTop_m = 0.75, kSleeveTop_m = 0.74;
const cv::Scalar kTableBgr(181, 212, 230), kSkinBgr(160, 195, 252), kSleeveBgr(107, 69, 56);

struct ArmPose {
  Eigen::Vector2d palm_px;  ///< palm centre pixel
  double angle_rad;         ///< arm axis (towards the fingers) from the image's +x
  double fingerLength_m;    ///< 0.08 relaxed, ~0.03 closed round an object
};

core::CameraIntrinsics camera() { return {600.0, 600.0, 319.5, 239.5, 640, 480}; }

/// Fills the box [along0, along1] x [-halfWidth, halfWidth] (metres, arm frame) in both images.
void drawBox(rawlog::RgbdFrame& f, const ArmPose& a, double along0, double along1, double halfWidth, double across,
             const cv::Scalar& bgr, double depth_m) {
  const double s = camera().fx_px / kHandTop_m;
  const Eigen::Vector2d x(std::cos(a.angle_rad), std::sin(a.angle_rad)), y(-x.y(), x.x());
  std::vector<cv::Point> poly;
  for (const auto& [l, w] : {std::pair{along0, -halfWidth}, {along1, -halfWidth}, {along1, halfWidth}, {along0, halfWidth}}) {
    const Eigen::Vector2d p = a.palm_px + s * (l * x + (w + across) * y);
    poly.emplace_back(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
  }
  cv::fillConvexPoly(f.colour_bgr8, poly, bgr);
  cv::fillConvexPoly(f.depth_m, poly, cv::Scalar(depth_m));
}

rawlog::RgbdFrame drawnFrame(int index, const std::optional<ArmPose>& arm) {
  rawlog::RgbdFrame f;
  f.index = index;
  f.t_s = index / 30.0;
  f.intrinsics = camera();
  f.colour_bgr8 = cv::Mat(480, 640, CV_8UC3, kTableBgr);
  f.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(kTable_m));
  if (!arm) return f;
  // The sleeve, its cuff where the detector expects it from the palm centre.
  const double cuff_m = -MarkerFreeHandDetector::Options{}.palmFromWrist_m;
  drawBox(f, *arm, -0.60, cuff_m, 0.038, 0.0, kSleeveBgr, kSleeveTop_m);
  drawBox(f, *arm, cuff_m, -0.045, 0.031, 0.0, kSkinBgr, kHandTop_m);     // wrist
  drawBox(f, *arm, -0.045, 0.045, 0.042, 0.0, kSkinBgr, kHandTop_m);      // palm
  for (const double across : {-0.030, -0.010, 0.010, 0.030})             // fingers
    drawBox(f, *arm, 0.045, 0.045 + arm->fingerLength_m, 0.008, across, kSkinBgr, kHandTop_m);
  drawBox(f, *arm, -0.02, 0.03, 0.01, 0.05, kSkinBgr, kHandTop_m);         // thumb
  return f;
}

Eigen::Vector3d palmPoint(const ArmPose& a) {
  const double z = kHandTop_m + MarkerFreeHandDetector::Options{}.palmDepth_m;
  const auto k = camera();
  return {(a.palm_px.x() - k.cx_px) * z / k.fx_px, (a.palm_px.y() - k.cy_px) * z / k.fy_px, z};
}

constexpr int kBackgroundFrames = 10;
constexpr double kPalmPixelTol_px = 4.0;   // 5 mm at 0.75 m
constexpr double kPalmTol_m = 0.005;

TEST(MarkerFreeHandDetector, PalmFromTheCuffWhateverTheFingersDo) {
  MarkerFreeHandDetector detector({});
  for (int i = 0; i < kBackgroundFrames; ++i) EXPECT_FALSE(detector.detect(drawnFrame(i, std::nullopt))) << i;
  // The arm from the top border, turning; the fingers closing from relaxed to round an object.
  for (int i = 0; i < 8; ++i) {
    const ArmPose arm{{300.0 + 10 * i, 250.0 + 5 * i}, (70.0 + 5.0 * i) * M_PI / 180, 0.08 - 0.007 * i};
    const auto h = detector.detect(drawnFrame(kBackgroundFrames + i, arm));
    ASSERT_TRUE(h.has_value()) << "frame " << i;
    EXPECT_TRUE(detector.lastGeometry().haveWrist) << "frame " << i;
    EXPECT_LT((h->palm_px - arm.palm_px).norm(), kPalmPixelTol_px) << "frame " << i;
    ASSERT_TRUE(h->hasDepth);
    EXPECT_LT((h->p_camera_palm_m - palmPoint(arm)).norm(), kPalmTol_m) << "frame " << i;
  }
  // The hand gone again: nothing reported.
  EXPECT_FALSE(detector.detect(drawnFrame(30, std::nullopt)).has_value());
}

// skinGapClose_m: a dark band drawn across the palm (a wire or tape on the skin, at the skin's depth) cuts
// the hand's skin in two. Closed at 0.02 m (a 17 px disc at the arm's median depth, 0.74 m) a 3 px wire
// (4 mm) is one skin region again; a 3 cm band (24 px) is wider than the disc and stays open.
int skinRegionsAcrossABand(double close_m, double band_m) {
  MarkerFreeHandDetector::Options o;
  o.skinGapClose_m = close_m;
  MarkerFreeHandDetector detector(o);
  for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(drawnFrame(i, std::nullopt));
  const ArmPose arm{{320.0, 260.0}, 80.0 * M_PI / 180, 0.08};
  auto f = drawnFrame(kBackgroundFrames, arm);
  drawBox(f, arm, -0.03 - band_m / 2, -0.03 + band_m / 2, 0.042, 0.0, {25, 20, 20}, kHandTop_m);
  detector.detect(f);
  cv::Mat labels;
  return cv::connectedComponents(detector.lastMask(), labels, 8) - 1;
}

TEST(MarkerFreeHandDetector, SkinGapsNarrowerThanTheDiscAreClosed) {
  constexpr double kWire_m = 3.0 / 800.0, kBand_m = 0.03;
  EXPECT_EQ(skinRegionsAcrossABand(0.0, kWire_m), 2) << "the wire should cut the skin without the closing";
  EXPECT_EQ(skinRegionsAcrossABand(0.02, kWire_m), 1);
  EXPECT_EQ(skinRegionsAcrossABand(0.02, kBand_m), 2) << "a band wider than the disc should stay open";
}

// minWorkingWidth_px: a frame three times as large as the drawn one (every pixel repeated 3 x 3, the
// intrinsics with it) is worked on at the drawn frame's size (640 px, the largest third of 1920 px that is
// at least 640 px wide), so the palm is the drawn frame's, mapped to
// the large frame's pixels (u_large = 3 (u + 0.5) - 0.5), at the same 3D position; lastMask() is the
// large frame's size and the drawn frame's mask enlarged.
TEST(MarkerFreeHandDetector, LargeFramesAtTheWorkingWidth) {
  auto enlarged = [](const rawlog::RgbdFrame& f) {
    rawlog::RgbdFrame big = f;
    cv::resize(f.colour_bgr8, big.colour_bgr8, {}, 3, 3, cv::INTER_NEAREST);
    cv::resize(f.depth_m, big.depth_m, {}, 3, 3, cv::INTER_NEAREST);
    const auto& k = f.intrinsics;
    big.intrinsics = {3 * k.fx_px, 3 * k.fy_px, 3 * (k.cx_px + 0.5) - 0.5, 3 * (k.cy_px + 0.5) - 0.5,
                      3 * k.width_px, 3 * k.height_px};
    return big;
  };
  MarkerFreeHandDetector::Options o;
  MarkerFreeHandDetector atOwnSize(o);  // 640 px: below twice minWorkingWidth_px, at its own size
  o.minWorkingWidth_px = 640;
  MarkerFreeHandDetector large(o);
  for (int i = 0; i < kBackgroundFrames; ++i) {
    EXPECT_FALSE(atOwnSize.detect(drawnFrame(i, std::nullopt)));
    EXPECT_FALSE(large.detect(enlarged(drawnFrame(i, std::nullopt))));
  }
  for (int i = 0; i < 6; ++i) {
    const ArmPose arm{{280.0 + 12 * i, 240.0 + 6 * i}, (65.0 + 6.0 * i) * M_PI / 180, 0.08 - 0.008 * i};
    const auto small = atOwnSize.detect(drawnFrame(kBackgroundFrames + i, arm));
    const auto h = large.detect(enlarged(drawnFrame(kBackgroundFrames + i, arm)));
    ASSERT_TRUE(small && h) << "frame " << i;
    const Eigen::Vector2d mapped = 3.0 * (small->palm_px.array() + 0.5) - 0.5;
    EXPECT_LT((h->palm_px - mapped).norm(), 1e-9) << "frame " << i;
    EXPECT_LT((h->p_camera_palm_m - small->p_camera_palm_m).norm(), 1e-12) << "frame " << i;
    EXPECT_LT((h->palm_px - 3.0 * (arm.palm_px.array() + 0.5).matrix() + Eigen::Vector2d::Constant(0.5)).norm(),
              3 * kPalmPixelTol_px)
        << "frame " << i;
    ASSERT_EQ(large.lastMask().size(), cv::Size(1920, 1440));
    cv::Mat up;
    cv::resize(atOwnSize.lastMask(), up, {}, 3, 3, cv::INTER_NEAREST);
    EXPECT_EQ(cv::countNonZero(up != large.lastMask()), 0) << "frame " << i;
    const Eigen::Vector2d entry = 3.0 * (atOwnSize.lastGeometry().entry_px.array() + 0.5) - 0.5;
    EXPECT_LT((large.lastGeometry().entry_px - entry).norm(), 1e-9) << "frame " << i;
  }
}

// A badge on the back of the hand that the hand's mask lacks (no depth there and the table's colour: neither
// foreground nor skin; a glove's tag plate in srp::synth's default view): the silhouette across the palm is
// the skin beside it, 17 mm wide on each side, which is no hand seen on its edge. The palm depth rule
// (palmHalfWidth_m) measures only cross-sections through the palm's centre line, so the palm stays half the
// palm's thickness under the back (counting the skin across the palm, thumb included: 8 mm off, 0/4 frames).
TEST(MarkerFreeHandDetector, BadgeCutOutOfTheHandIsNoNarrowHand) {
  MarkerFreeHandDetector detector({});
  for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(drawnFrame(i, std::nullopt));
  for (int i = 0; i < 4; ++i) {
    const ArmPose arm{{320.0 + 8 * i, 250.0}, (80.0 + 6.0 * i) * M_PI / 180, 0.08};
    auto f = drawnFrame(kBackgroundFrames + i, arm);
    drawBox(f, arm, -0.032, 0.032, 0.025, 0.0, kTableBgr, 0.0);  // 64 x 50 mm, over the palm centre
    const auto h = detector.detect(f);
    ASSERT_TRUE(h.has_value()) << "frame " << i;
    ASSERT_TRUE(h->hasDepth) << "frame " << i;
    EXPECT_LT((h->palm_px - arm.palm_px).norm(), kPalmPixelTol_px) << "frame " << i;
    EXPECT_LT((h->p_camera_palm_m - palmPoint(arm)).norm(), kPalmTol_m) << "frame " << i;
  }
}

TEST(MarkerFreeHandDetector, DepthHolesOnTheHand) {
  MarkerFreeHandDetector detector({});
  for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(drawnFrame(i, std::nullopt));
  const ArmPose arm{{330.0, 260.0}, 100.0 * M_PI / 180, 0.08};
  // A moving hand on a ToF camera: blobs of missing depth over 60 % of the arm.
  auto f = drawnFrame(kBackgroundFrames, arm);
  const cv::Mat arm0 = f.depth_m < kTable_m - 0.05;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> u(0, 639), v(0, 479);
  for (int n = 0; n < 3000; ++n) {
    const cv::Point c(u(rng), v(rng));
    if (arm0.at<uchar>(c)) cv::circle(f.depth_m, c, 12, cv::Scalar(0.0), cv::FILLED);
  }
  const cv::Mat armHoles = arm0 & (f.depth_m == 0.0);
  ASSERT_GT(2 * cv::countNonZero(armHoles), cv::countNonZero(arm0)) << "the test should leave < 50 % valid arm depth";
  auto h = detector.detect(f);
  ASSERT_TRUE(h.has_value());
  EXPECT_LT((h->palm_px - arm.palm_px).norm(), kPalmPixelTol_px);
  ASSERT_TRUE(h->hasDepth);
  EXPECT_LT((h->p_camera_palm_m - palmPoint(arm)).norm(), kPalmTol_m);
  // No depth at all on the arm: the pixel still (scale from the last depth), no depth.
  f = drawnFrame(kBackgroundFrames + 1, arm);
  f.depth_m.setTo(0.0, f.depth_m < kTable_m - 0.05);
  h = detector.detect(f);
  ASSERT_TRUE(h.has_value());
  EXPECT_FALSE(h->hasDepth);
  EXPECT_LT((h->palm_px - arm.palm_px).norm(), kPalmPixelTol_px);
}

// A static object whose outline is a depth shadow (no depth) except while
// the demonstrator's arm covers it, as a structured-light camera drops depth
// at steps: in the whole-recording background that band's quantile is the
// arm (its only valid samples), which cut the hand off at the wrist (HRT1
// task2 under depth edge holes). minBackgroundValidFraction fills it from its
// trusted neighbours.
TEST(MarkerFreeHandDetector, ArmAcrossAStaticObjectsDepthShadow) {
  const ArmPose arm{{320.0, 300.0}, 90.0 * M_PI / 180, 0.08};  // from the top border; cuff ~104 px above the palm
  const cv::Rect box(240, 240, 170, 150);  // its top edge crosses the bare wrist
  constexpr double kBoxTop_m = 0.80;
  constexpr int kShadow_px = 3;  // on each side of the box's outline
  constexpr int kFrames = 20, kArmFrom = 14;  // the arm in 6 of 20 frames: the band has depth in 30 % of them
  cv::Mat band(480, 640, CV_8UC1, cv::Scalar(0));
  cv::rectangle(band, box, cv::Scalar(255), 2 * kShadow_px);
  std::vector<rawlog::RgbdFrame> frames;
  for (int i = 0; i < kFrames; ++i) {
    auto f = drawnFrame(i, i >= kArmFrom ? std::optional<ArmPose>(arm) : std::nullopt);
    const cv::Mat armMask = f.depth_m < kBoxTop_m - 0.02;
    f.colour_bgr8.setTo(kSkinBgr, armMask);  // a bare forearm: the palm is placed from the arm's far end
    cv::Mat boxMask(480, 640, CV_8UC1, cv::Scalar(0));
    boxMask(box).setTo(255);
    boxMask &= ~armMask;
    f.depth_m.setTo(kBoxTop_m, boxMask);
    f.colour_bgr8.setTo(cv::Scalar(150, 150, 150), boxMask);
    f.depth_m.setTo(0.0, band & ~armMask);
    frames.push_back(f);
  }
  // Far-end rule: palmFromFarEnd_m back from the fingertips (0.045 + 0.08 m from the drawn palm centre).
  const MarkerFreeHandDetector::Options defaults;
  const Eigen::Vector2d farEndPalm_px =
      arm.palm_px + camera().fx_px / kHandTop_m * (0.045 + arm.fingerLength_m - defaults.palmFromFarEnd_m) *
                        Eigen::Vector2d(std::cos(arm.angle_rad), std::sin(arm.angle_rad));
  constexpr double kFarEndTol_px = 8.0;  // 1 cm at 0.75 m
  auto run = [&](const MarkerFreeHandDetector::Options& o) {
    MarkerFreeHandDetector detector(o);
    for (const auto& f : frames) detector.preview(f);
    int within = 0;
    for (const auto& f : frames) {
      const auto h = detector.detect(f);
      if (f.index < kArmFrom) EXPECT_FALSE(h.has_value()) << "frame " << f.index << ": no arm in view";
      else if (h && (h->palm_px - farEndPalm_px).norm() < kFarEndTol_px) ++within;
    }
    return within;
  };
  EXPECT_EQ(run(defaults), kFrames - kArmFrom);
  MarkerFreeHandDetector::Options off;
  off.minBackgroundValidFraction = 0.0;  // each pixel's own quantile: the arm is background on the band
  EXPECT_EQ(run(off), 0) << "the scene should cut the hand off at the wrist without the fill";
}

// A wall beyond the depth sensor's range behind the arm (a side view: the
// top of the image shows the far wall, never a depth there): the arm has a
// depth where it passes in front of the wall, and nowhere else does. The arm
// enters from the image's top edge (farWithoutDepth, minFieldOfViewValid);
// with each such pixel's own quantile (the arm's depth) and a field of view
// that starts below the wall, the arm was cut at the wall's lower edge and
// entered "there".
TEST(MarkerFreeHandDetector, ArmInFrontOfAWallWithoutDepth) {
  constexpr int kWallRows = 280;  // rows 0..279: the wall, no depth but on the arm
  constexpr int kFrames = 20, kArmFrom = 12;
  const cv::Scalar kWallBgr(70, 70, 70);
  std::vector<rawlog::RgbdFrame> frames;
  std::vector<ArmPose> arms(kFrames, ArmPose{{0.0, 0.0}, 0.0, 0.0});
  for (int i = 0; i < kFrames; ++i) {
    arms[i] = ArmPose{{280.0 + 10.0 * (i - kArmFrom), 330.0}, 90.0 * M_PI / 180, 0.08};  // from the top border
    auto f = drawnFrame(i, i >= kArmFrom ? std::optional<ArmPose>(arms[i]) : std::nullopt);
    const cv::Mat armMask = f.depth_m < kTable_m - 0.02;
    f.colour_bgr8.setTo(kSkinBgr, armMask);  // a bare forearm: the palm is placed from the arm's far end
    cv::Mat wall(480, 640, CV_8UC1, cv::Scalar(0));
    wall.rowRange(0, kWallRows).setTo(255);
    wall &= ~armMask;
    f.depth_m.setTo(0.0, wall);
    f.colour_bgr8.setTo(kWallBgr, wall);
    frames.push_back(f);
  }
  const MarkerFreeHandDetector::Options defaults;
  constexpr double kFarEndTol_px = 8.0;  // 1 cm at 0.75 m
  auto run = [&](const MarkerFreeHandDetector::Options& o, int& fromTopEdge) {
    MarkerFreeHandDetector detector(o);
    for (const auto& f : frames) detector.preview(f);
    int within = 0;
    fromTopEdge = 0;
    for (const auto& f : frames) {
      const auto h = detector.detect(f);
      if (f.index < kArmFrom) {
        EXPECT_FALSE(h.has_value()) << "frame " << f.index << ": no arm in view";
        continue;
      }
      // Far-end rule: palmFromFarEnd_m back from the fingertips (0.045 + 0.08 m from the drawn palm centre).
      const ArmPose& arm = arms[static_cast<std::size_t>(f.index)];
      const Eigen::Vector2d farEndPalm_px =
          arm.palm_px + camera().fx_px / kHandTop_m * (0.045 + arm.fingerLength_m - o.palmFromFarEnd_m) *
                            Eigen::Vector2d(std::cos(arm.angle_rad), std::sin(arm.angle_rad));
      if (h && (h->palm_px - farEndPalm_px).norm() < kFarEndTol_px) ++within;
      if (h && detector.lastGeometry().entry_px.y() <= o.borderMargin_px) ++fromTopEdge;
    }
    return within;
  };
  int fromTopEdge = 0;
  EXPECT_EQ(run(defaults, fromTopEdge), kFrames - kArmFrom);
  EXPECT_EQ(fromTopEdge, kFrames - kArmFrom) << "the arm enters from the image's top edge";
  MarkerFreeHandDetector::Options off;
  off.farWithoutDepth = false;
  off.minFieldOfViewValid = 0.5;
  run(off, fromTopEdge);
  EXPECT_EQ(fromTopEdge, 0) << "the scene should cut the arm at the wall's lower edge without the rule";
}

// Seen from the side: a bare forearm enters from the right edge in front of a
// wall beyond the depth sensor's range (no depth above the table, except a
// cupboard within range at the left), below a band at the top where the depth
// camera sees nothing. The depth-less run from the top edge reaches down to
// the arm's upper edge along its whole length; only its first rows are the
// band the arm may enter through (maxBandParallax_px): the arm enters at the
// right edge and the palm lies at its far end.
TEST(MarkerFreeHandDetector, ArmBelowADepthlessWallEntersFromTheSide) {
  constexpr int kBandRows = 40, kWallBottom = 200, kCupboardCols = 100;  // cupboard: 15 % of the columns
  constexpr int kFrames = 16;
  const cv::Scalar kWallBgr(70, 70, 70);
  const ArmPose arm{{250.0, 170.0}, M_PI, 0.08};  // pointing left, the forearm leaves at the right edge
  auto frame = [&](int index, bool withArm) {
    auto f = drawnFrame(index, withArm ? std::optional<ArmPose>(arm) : std::nullopt);
    const cv::Mat armMask = f.depth_m < kTable_m - 0.02;
    f.colour_bgr8.setTo(kSkinBgr, armMask);  // bare forearm
    cv::Mat wall(480, 640, CV_8UC1, cv::Scalar(0));
    wall.rowRange(0, kWallBottom).setTo(255);
    wall &= ~armMask;
    f.depth_m.setTo(0.0, wall);
    f.colour_bgr8.setTo(kWallBgr, wall);
    f.depth_m(cv::Rect(0, kBandRows, kCupboardCols, kWallBottom - kBandRows)).setTo(2.0);
    f.depth_m.rowRange(0, kBandRows).setTo(0.0);
    return f;
  };
  const Eigen::Vector2d farEndPalm_px =
      arm.palm_px + camera().fx_px / kHandTop_m * (0.045 + arm.fingerLength_m - MarkerFreeHandDetector::Options{}.palmFromFarEnd_m) *
                        Eigen::Vector2d(std::cos(arm.angle_rad), std::sin(arm.angle_rad));
  constexpr double kFarEndTol_px = 8.0;  // 1 cm at 0.75 m
  auto run = [&](const MarkerFreeHandDetector::Options& o) {
    MarkerFreeHandDetector detector(o);
    for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(frame(i, false));
    int within = 0;
    for (int i = kBackgroundFrames; i < kFrames; ++i) {
      const auto h = detector.detect(frame(i, true));
      if (h && (h->palm_px - farEndPalm_px).norm() < kFarEndTol_px) ++within;
    }
    return within;
  };
  EXPECT_EQ(run({}), kFrames - kBackgroundFrames);
  MarkerFreeHandDetector::Options off;
  off.maxBandParallax_px = -1;
  EXPECT_EQ(run(off), 0) << "the scene should take the arm's upper edge for where it enters without the rule";
}

// A bare forearm reaching with an open hand (fingers 8 cm) and holding with a closed one (fingers
// 3 cm, curled round a part): the skin's far end is the fingertips or the curled fingers. The palm, the
// hand's thickest part (42 mm half-width against the wrist's 31 mm), lies past halfway between the
// two lengths from the far end on the open hand (farEndOpenHand): its palm is placed
// palmFromFingertips_m back, not palmFromFarEnd_m (on the fingers, 5.5 cm off).
namespace openhand {
constexpr double kTol_px = 8.0;  // 1 cm at 0.75 m: the drawn lengths are the detector's to a few mm
constexpr double kOpen_m = 0.08, kClosed_m = 0.03;

rawlog::RgbdFrame bareFrame(int index, const std::optional<ArmPose>& arm, bool holding) {
  auto f = drawnFrame(index, arm);
  f.colour_bgr8.setTo(kSkinBgr, f.depth_m < kTable_m - 0.02);  // bare forearm
  // A blue part joined to the fingertips, standing 1 cm above the hand.
  if (arm && holding) drawBox(f, *arm, 0.045 + arm->fingerLength_m, 0.20, 0.035, 0.0, {200, 60, 40}, kHandTop_m - 0.01);
  return f;
}

/// Palms (of 6 frames) within kTol_px of `expected(arm)`.
int palmsNear(bool rule, double fingerLength_m, bool holding,
              const std::function<Eigen::Vector2d(const ArmPose&)>& expected) {
  MarkerFreeHandDetector::Options o;
  o.farEndOpenHand = rule;
  MarkerFreeHandDetector detector(o);
  for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(bareFrame(i, std::nullopt, false));
  int within = 0;
  for (int i = 0; i < 6; ++i) {
    const ArmPose arm{{300.0 + 8 * i, 230.0 + 4 * i}, (80.0 + 4.0 * i) * M_PI / 180, fingerLength_m};
    const auto h = detector.detect(bareFrame(kBackgroundFrames + i, arm, holding));
    if (h && detector.lastGeometry().bareForearm && (h->palm_px - expected(arm)).norm() < kTol_px) ++within;
  }
  return within;
}

Eigen::Vector2d truePalm(const ArmPose& a) { return a.palm_px; }
}  // namespace openhand

TEST(MarkerFreeHandDetector, OpenHandFromItsThickestPoint) {
  using namespace openhand;
  EXPECT_EQ(palmsNear(true, kOpen_m, false, truePalm), 6);
  EXPECT_EQ(palmsNear(true, kClosed_m, false, truePalm), 6);
  EXPECT_EQ(palmsNear(false, kOpen_m, false, truePalm), 0) << "the open hand's palm should land on its fingers without the rule";
  EXPECT_EQ(palmsNear(false, kClosed_m, false, truePalm), 6);
}

// The same open hand's skin with a part joined past its fingertips (the arm's foreground goes on past
// the skin's far end): a hand holding a part is closed round it, its far end the curled fingers, and the
// palm is placed palmFromFarEnd_m back, as without farEndOpenHand (the drawn fingers are long: the palm
// lands on them, where the rule's absence puts it).
TEST(MarkerFreeHandDetector, HandJoinedToAPartPastItsFarEndIsClosed) {
  using namespace openhand;
  const MarkerFreeHandDetector::Options o;
  auto closedReading = [&](const ArmPose& a) {
    const double s = camera().fx_px / kHandTop_m;
    const double along_m = 0.045 + a.fingerLength_m - o.palmFromFarEnd_m;
    return Eigen::Vector2d(a.palm_px + along_m * s * Eigen::Vector2d(std::cos(a.angle_rad), std::sin(a.angle_rad)));
  };
  EXPECT_EQ(palmsNear(false, kOpen_m, true, closedReading), 6);
  EXPECT_EQ(palmsNear(true, kOpen_m, true, closedReading), 6) << "a hand holding a part should read closed";
}

// A hand hanging from a flexed wrist, seen from the side (HRT1 task3's first frames: the hand above the
// table before it reaches down): the forearm enters from the right, the hand (its palm seen on its edge
// with the thumb, 7 cm across, 9 cm long, and the curled fingers) turns 55 degrees down from it. The
// distance transform is largest where the hand joins the forearm, 10 cm from the far end, with the
// forearm narrower behind it, as on an open hand; the breadth across the forearm's axis is largest within
// palmFromFarEnd_m of the far end (the hanging hand's span): closed, the palm palmFromFarEnd_m back.
TEST(MarkerFreeHandDetector, HandHangingFromAFlexedWristIsClosed) {
  const MarkerFreeHandDetector::Options defaults;
  MarkerFreeHandDetector::Options o;
  o.farEndOpenHand = true;
  auto frame = [&](int index, const std::optional<Eigen::Vector2d>& wrist_px) {
    auto f = drawnFrame(index, std::nullopt);
    if (!wrist_px) return f;
    const ArmPose forearm{*wrist_px, M_PI, 0.0}, hand{*wrist_px, M_PI - 55.0 * M_PI / 180, 0.0};
    drawBox(f, forearm, -0.60, 0.0, 0.022, 0.0, kSkinBgr, kHandTop_m);
    drawBox(f, hand, -0.02, 0.09, 0.035, 0.0, kSkinBgr, kHandTop_m);   // palm on its edge, with the thumb
    drawBox(f, hand, 0.09, 0.13, 0.02, -0.01, kSkinBgr, kHandTop_m);   // curled fingers
    return f;
  };
  const double s_px = camera().fx_px / kHandTop_m;
  auto run = [&](const MarkerFreeHandDetector::Options& opts, std::vector<double>& back_m) {
    MarkerFreeHandDetector detector(opts);
    for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(frame(i, std::nullopt));
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector2d wrist_px(420.0 + 6 * i, 200.0 + 3 * i);
      const auto h = detector.detect(frame(kBackgroundFrames + i, wrist_px));
      ASSERT_TRUE(h.has_value()) << "frame " << i;
      const auto& g = detector.lastGeometry();
      ASSERT_TRUE(g.bareForearm) << "frame " << i;
      back_m.push_back((g.farEnd_px - h->palm_px).norm() / s_px);
    }
  };
  constexpr double kTol_m = 0.01;  // the drawn hand is flat: the walk is in the image plane to a few mm
  std::vector<double> closed, withoutRule;
  run(o, closed);
  run(defaults, withoutRule);
  for (std::size_t i = 0; i < closed.size(); ++i) {
    std::printf("hanging hand, frame %zu: palm %.3f m from the far end (%.3f m without farEndOpenHand)\n", i,
                closed[i], withoutRule[i]);
    EXPECT_NEAR(closed[i], defaults.palmFromFarEnd_m, kTol_m) << "frame " << i << ": read as an open hand";
  }
}

// The palm's distance from a bare forearm's far end by the view (palmFromFarEndAlongRay_m,
// palmFromFarEndAcrossRay_m). The arm and hand are drawn as boxes on a plane in 3D and projected
// exactly (each pixel's depth where its ray meets the plane): an open hand (fingers 8 cm) lying across
// the camera's ray, its far end the fingertips 0.125 m from the palm centre, and a closed hand (fingers
// curled to 2 cm, far end 0.065 m from the palm) pointing 50 deg away from the camera, the arm entering
// from the image's bottom edge nearer the camera, as an egocentric camera sees it from above and behind.
namespace byview {
struct PlaneArm {
  Eigen::Vector3d palm_m;  ///< palm centre on the back of the hand (camera frame)
  Eigen::Vector3d x, y;    ///< unit, along the arm towards the fingers and across it, in the hand's plane
  double fingerLength_m;
};

void drawPlaneBox(rawlog::RgbdFrame& f, const PlaneArm& a, double along0, double along1, double halfWidth,
                  double across) {
  const auto k = camera();
  std::vector<cv::Point> poly;
  const std::pair<double, double> corners[] = {{along0, -halfWidth}, {along1, -halfWidth}, {along1, halfWidth},
                                                {along0, halfWidth}};
  for (const auto& [l, w] : corners) {
    const Eigen::Vector3d p = a.palm_m + l * a.x + (w + across) * a.y;
    poly.emplace_back(static_cast<int>(std::lround(k.fx_px * p.x() / p.z() + k.cx_px)),
                      static_cast<int>(std::lround(k.fy_px * p.y() / p.z() + k.cy_px)));
  }
  cv::Mat inside(f.depth_m.size(), CV_8UC1, cv::Scalar(0));
  cv::fillConvexPoly(inside, poly, cv::Scalar(255));
  const Eigen::Vector3d n = a.x.cross(a.y);
  for (int v = 0; v < inside.rows; ++v)
    for (int u = 0; u < inside.cols; ++u) {
      if (!inside.at<uchar>(v, u)) continue;
      const Eigen::Vector3d ray((u - k.cx_px) / k.fx_px, (v - k.cy_px) / k.fy_px, 1.0);
      f.depth_m.at<float>(v, u) = static_cast<float>(a.palm_m.dot(n) / ray.dot(n));
      f.colour_bgr8.at<cv::Vec3b>(v, u) = cv::Vec3b(160, 195, 252);  // kSkinBgr: a bare forearm
    }
}

rawlog::RgbdFrame planeFrame(int index, const std::optional<PlaneArm>& arm) {
  auto f = drawnFrame(index, std::nullopt);
  if (!arm) return f;
  drawPlaneBox(f, *arm, -0.45, -0.045, 0.031, 0.0);  // forearm and wrist
  drawPlaneBox(f, *arm, -0.045, 0.045, 0.042, 0.0);  // palm
  for (const double across : {-0.030, -0.010, 0.010, 0.030})  // fingers
    drawPlaneBox(f, *arm, 0.045, 0.045 + arm->fingerLength_m, 0.008, across);
  drawPlaneBox(f, *arm, -0.02, 0.03, 0.01, 0.05);  // thumb
  return f;
}

/// The palms' pixel distance from the true palm centre's pixel, 6 frames moving slightly.
std::vector<double> palmErrors_px(const MarkerFreeHandDetector::Options& o, double tilt_rad, double fingerLength_m) {
  const auto k = camera();
  MarkerFreeHandDetector detector(o);
  for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(planeFrame(i, std::nullopt));
  std::vector<double> out;
  for (int i = 0; i < 6; ++i) {
    // Pointing up the image (away from the bottom edge where the arm enters), tilted away from the camera.
    const double yaw = (-90.0 + 3.0 * i) * M_PI / 180;
    PlaneArm a{{0.01 * i, 0.06, kHandTop_m},
               {std::cos(yaw) * std::cos(tilt_rad), std::sin(yaw) * std::cos(tilt_rad), std::sin(tilt_rad)},
               {-std::sin(yaw), std::cos(yaw), 0.0},
               fingerLength_m};
    const auto h = detector.detect(planeFrame(kBackgroundFrames + i, a));
    if (!h || !detector.lastGeometry().bareForearm) {
      out.push_back(1e9);
      continue;
    }
    const Eigen::Vector2d truth(k.fx_px * a.palm_m.x() / a.palm_m.z() + k.cx_px,
                                k.fy_px * a.palm_m.y() / a.palm_m.z() + k.cy_px);
    out.push_back((h->palm_px - truth).norm());
  }
  return out;
}
}  // namespace byview

TEST(MarkerFreeHandDetector, PalmFromTheFarEndByTheView) {
  using namespace byview;
  // 1.5 cm at 0.75 m: the rule's lengths are the renders' (across the ray 0.12 m against the drawn open
  // hand's 0.125 m); the fixed lengths miss by 4-6 cm.
  constexpr double kTol_px = 12.0;
  constexpr double kOpen_m = 0.08, kCurled_m = 0.02, kAcross_rad = 0.0, kAway_rad = 50.0 * M_PI / 180;
  MarkerFreeHandDetector::Options byView, fixed, longer;
  byView.palmFromFarEndAlongRay_m = 0.045;
  byView.palmFromFarEndAcrossRay_m = 0.12;
  longer.palmFromFarEnd_m = 0.12;  // one constant for both: the hand seen across the ray's
  auto within = [&](const std::vector<double>& e) {
    return std::count_if(e.begin(), e.end(), [&](double x) { return x < kTol_px; });
  };
  const auto acrossByView = palmErrors_px(byView, kAcross_rad, kOpen_m);
  const auto awayByView = palmErrors_px(byView, kAway_rad, kCurled_m);
  const auto acrossFixed = palmErrors_px(fixed, kAcross_rad, kOpen_m);
  const auto awayLonger = palmErrors_px(longer, kAway_rad, kCurled_m);
  for (std::size_t i = 0; i < acrossByView.size(); ++i)
    std::printf("by the view, frame %zu: across the ray %.1f px (palmFromFarEnd_m %.1f px), pointing away %.1f px "
                "(0.12 m: %.1f px)\n",
                i, acrossByView[i], acrossFixed[i], awayByView[i], awayLonger[i]);
  EXPECT_EQ(within(acrossByView), 6);
  EXPECT_EQ(within(awayByView), 6);
  EXPECT_EQ(within(acrossFixed), 0) << "palmFromFarEnd_m should put the open hand's palm on its fingers";
  EXPECT_EQ(within(awayLonger), 0) << "the open hand's length should put the curled hand's palm on its wrist";
}

// A bare forearm in every frame of the recording, nearly still (swept
// kSweep_px over the clip, as a hand holding a part while the head-mounted
// camera looks down at it), over a table of a skin-like colour, beside a
// static box on the table: the whole-recording background's quantile is the
// arm itself wherever the arm always is. A skin-coloured region standing
// above the support plane that reaches the border and is shaped like a
// forearm is the arm, not the background (with the defaults); the box, not
// skin-coloured, stays background.
TEST(MarkerFreeHandDetector, StillBareForearmInEveryFrame) {
  constexpr int kFrames = 30;
  auto withArm = [](int index, const std::optional<ArmPose>& arm) {
    auto f = drawnFrame(index, arm);
    f.colour_bgr8.setTo(kSkinBgr, f.depth_m < kTable_m - 0.02);  // bare forearm
    const cv::Rect box(460, 300, 80, 60);  // a green box on the table, 8 cm high
    cv::rectangle(f.colour_bgr8, box, cv::Scalar(40, 120, 40), cv::FILLED);
    cv::rectangle(f.depth_m, box, cv::Scalar(kTable_m - 0.08), cv::FILLED);
    return f;
  };
  for (const double kSweep_px : {0.0, 30.0}) {
    SCOPED_TRACE("swept " + std::to_string(kSweep_px) + " px");
    std::vector<rawlog::RgbdFrame> frames;
    for (int i = 0; i < kFrames; ++i) {
      const double s = kSweep_px * std::sin(2.0 * M_PI * i / kFrames);
      frames.push_back(withArm(i, ArmPose{{300.0 + s, 280.0 + 0.3 * s}, 80.0 * M_PI / 180, 0.08}));  // from the top
    }
    // The reference: the palm found against the hand-free scene (first-frames
    // background), i.e. what the whole-recording background should give.
    std::vector<Eigen::Vector2d> reference;
    {
      MarkerFreeHandDetector detector({});
      for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(withArm(i, std::nullopt));
      for (auto f : frames) {
        f.index += kBackgroundFrames;
        const auto h = detector.detect(f);
        ASSERT_TRUE(h.has_value());
        reference.push_back(h->palm_px);
      }
    }
    const MarkerFreeHandDetector::Options on;  // the defaults
    ASSERT_TRUE(on.stillArmFromPlane);
    auto run = [&](const MarkerFreeHandDetector::Options& o) {
      MarkerFreeHandDetector detector(o);
      for (const auto& f : frames) detector.preview(f);
      int within = 0;
      for (const auto& f : frames) {
        const auto h = detector.detect(f);
        if (h && (h->palm_px - reference[static_cast<std::size_t>(f.index)]).norm() < kPalmPixelTol_px) ++within;
      }
      return within;
    };
    constexpr double kMinShareWithin = 0.9;
    const int within = run(on);
    EXPECT_GE(within, kMinShareWithin * kFrames) << within << " of " << kFrames << " palms within tolerance";
    MarkerFreeHandDetector::Options off;
    off.stillArmFromPlane = false;
    const int withinOff = run(off);
    std::printf("still bare forearm, swept %.0f px: %d of %d palms within %.0f px (%d without the plane rule)\n",
                kSweep_px, within, kFrames, kPalmPixelTol_px, withinOff);
    if (kSweep_px == 0.0) EXPECT_LT(withinOff, kMinShareWithin * kFrames) << "the scene should fail without the rule";
  }
  // The still arm's palm where the far-end rule puts it on the drawn hand.
  const ArmPose arm{{300.0, 280.0}, 80.0 * M_PI / 180, 0.08};
  MarkerFreeHandDetector detector({});
  for (int i = 0; i < kFrames; ++i) detector.preview(withArm(i, arm));
  const auto h = detector.detect(withArm(0, arm));
  ASSERT_TRUE(h.has_value());
  const Eigen::Vector2d farEndPalm_px =
      arm.palm_px + camera().fx_px / kHandTop_m * (0.045 + arm.fingerLength_m - detector.options().palmFromFarEnd_m) *
                        Eigen::Vector2d(std::cos(arm.angle_rad), std::sin(arm.angle_rad));
  EXPECT_LT((h->palm_px - farEndPalm_px).norm(), kPalmPixelTol_px);
}

// A still box of the arm's own skin colour, 20 x 25 cm and 8 cm high, on
// the table in every frame, reaching the image's left border (a tan box, a
// bread bin), while a bare forearm moves beside it: a still region of skin
// colour above the table that reaches the border, but not shaped like an arm
// (wider than a forearm, not elongated). It stays background; without the
// shape test it is taken for a still arm, foreground in every frame, and the
// palm lands on it.
TEST(MarkerFreeHandDetector, StillSkinColouredBoxAtTheBorderIsNoArm) {
  constexpr int kFrames = 30;
  constexpr double kBoxTop_m = kTable_m - 0.08;
  const cv::Rect box(0, 150, 156, 195);  // 0.20 x 0.25 m at its top's depth, from the left border
  auto withArm = [&](int index, const std::optional<ArmPose>& arm) {
    auto f = drawnFrame(index, arm);
    f.colour_bgr8.setTo(kSkinBgr, f.depth_m < kTable_m - 0.02);  // bare forearm
    cv::rectangle(f.colour_bgr8, box, kSkinBgr, cv::FILLED);
    cv::rectangle(f.depth_m, box, cv::Scalar(kBoxTop_m), cv::FILLED);
    return f;
  };
  // The arm enters from the top border and sweeps 200 px beside the box.
  auto armAt = [](int i) { return ArmPose{{340.0 + 200.0 * i / (kFrames - 1), 280.0}, 80.0 * M_PI / 180, 0.08}; };
  // The reference: the palm found against the hand-free scene (first-frames background).
  std::vector<Eigen::Vector2d> reference;
  {
    MarkerFreeHandDetector detector({});
    for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(withArm(i, std::nullopt));
    for (int i = 0; i < kFrames; ++i) {
      const auto h = detector.detect(withArm(kBackgroundFrames + i, armAt(i)));
      ASSERT_TRUE(h.has_value());
      reference.push_back(h->palm_px);
    }
  }
  auto run = [&](const MarkerFreeHandDetector::Options& o) {
    MarkerFreeHandDetector detector(o);
    for (int i = 0; i < kFrames; ++i) detector.preview(withArm(i, armAt(i)));
    int within = 0;
    for (int i = 0; i < kFrames; ++i) {
      const auto h = detector.detect(withArm(i, armAt(i)));
      if (h && (h->palm_px - reference[static_cast<std::size_t>(i)]).norm() < kPalmPixelTol_px) ++within;
    }
    return within;
  };
  constexpr double kMinShareWithin = 0.9;
  const MarkerFreeHandDetector::Options defaults;
  ASSERT_TRUE(defaults.stillArmFromPlane);
  const int within = run(defaults);
  EXPECT_GE(within, kMinShareWithin * kFrames) << within << " of " << kFrames << " palms within tolerance";
  MarkerFreeHandDetector::Options anyRegion;
  anyRegion.stillArmShapeShare = 0.0;  // any skin-coloured region at the border is a still arm
  const int withinAnyRegion = run(anyRegion);
  std::printf("still skin-coloured box at the border: %d of %d palms within %.0f px (%d without the shape test)\n",
              within, kFrames, kPalmPixelTol_px, withinAnyRegion);
  EXPECT_LT(withinAnyRegion, kMinShareWithin * kFrames) << "the scene should fail without the shape test";
}

// A sleeved arm holding a part of a skin-like colour (a tan toy, a red part's
// shaded face) that reaches 0.20 m beyond the fingers: the skin blob is longer
// than a hand, which alone would make it a bare forearm whose far end is the
// part's. The cuff in view places the palm (cuffFirst).
TEST(MarkerFreeHandDetector, SkinColouredHeldPartDoesNotMoveThePalmPastTheCuff) {
  const ArmPose arm{{320.0, 200.0}, 80.0 * M_PI / 180, 0.03};  // from the top border, fingers closed round the part
  constexpr double kPartLength_m = 0.20, kPartHalfWidth_m = 0.03;
  auto frameWithPart = [&](int index) {
    auto f = drawnFrame(index, arm);
    drawBox(f, arm, 0.045, 0.045 + kPartLength_m, kPartHalfWidth_m, 0.0, kSkinBgr, kHandTop_m + 0.02);
    return f;
  };
  auto run = [&](const MarkerFreeHandDetector::Options& o) {
    MarkerFreeHandDetector detector(o);
    for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(drawnFrame(i, std::nullopt));
    const auto h = detector.detect(frameWithPart(kBackgroundFrames));
    return h ? std::optional<Eigen::Vector2d>(h->palm_px) : std::nullopt;
  };
  const auto palm = run({});
  ASSERT_TRUE(palm.has_value());
  EXPECT_LT((*palm - arm.palm_px).norm(), kPalmPixelTol_px);
  MarkerFreeHandDetector::Options off;
  off.cuffFirst = false;
  const auto farEnd = run(off);
  ASSERT_TRUE(farEnd.has_value());
  // Without the rule the palm lies palmFromFarEnd_m back from the part's far end: on the part.
  constexpr double kOnThePart_px = 40.0;  // 5 cm at 0.75 m
  EXPECT_GT((*farEnd - arm.palm_px).norm(), kOnThePart_px) << "the scene should move the palm without the rule";
}

TEST(MarkerFreeHandDetector, EnteringHandFromItsFingertips) {
  MarkerFreeHandDetector detector({});
  for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(drawnFrame(i, std::nullopt));
  // The wrist still outside the image (skin on the border): no cuff, the palm
  // is found back from the fingertips (relaxed fingers).
  const ArmPose arm{{320.0, 40.0}, 90.0 * M_PI / 180, 0.08};
  const auto h = detector.detect(drawnFrame(kBackgroundFrames, arm));
  ASSERT_TRUE(h.has_value());
  EXPECT_FALSE(detector.lastGeometry().haveWrist);
  constexpr double kFromFingertipsTol_px = 12.0;  // 15 mm: the relaxed fingers' length is a guess
  EXPECT_LT((h->palm_px - arm.palm_px).norm(), kFromFingertipsTol_px);
}

// A red part standing on the table away from the arm (no border contact: an island of foreground), its
// face towards the camera in shade, under a white lamp and under a cold one (R 0.85, G 0.93, B 1.0 in
// linear light, the renders' ColdLight). YCrCb's chroma grows with brightness: the shaded red (Y 36-40,
// Cr 158-160) has a bright skin's Cr and is inside the prior box, so without skinMaxChromaPerLuma it is
// skin under both lamps and, alone in the frame, reported as a hand. With it the part is no skin under
// either lamp, and the sleeved arm's hand mask and palm are the same under both lamps.
namespace lamp {
const cv::Scalar kShadedRedBgr(16, 20, 84);
const cv::Rect kPart(420, 300, 90, 70);  // 0.11 x 0.09 m at the part's depth, away from every border
constexpr double kPartTop_m = kTable_m - 0.06;

/// The drawn frame (with the red part), its encoded colour as under the lamp of linear-light gains `rgb`.
rawlog::RgbdFrame litFrame(int index, const std::optional<ArmPose>& arm, bool part, const Eigen::Vector3d& rgb) {
  auto f = drawnFrame(index, arm);
  if (part) {
    cv::rectangle(f.colour_bgr8, kPart, kShadedRedBgr, cv::FILLED);
    cv::rectangle(f.depth_m, kPart, cv::Scalar(kPartTop_m), cv::FILLED);
  }
  constexpr double kInverseGamma = 1.0 / 2.2;  // the camera's encoding: a linear gain g scales 8-bit values by g^(1/2.2)
  cv::multiply(f.colour_bgr8,
               cv::Scalar(std::pow(rgb.z(), kInverseGamma), std::pow(rgb.y(), kInverseGamma),
                          std::pow(rgb.x(), kInverseGamma)),
               f.colour_bgr8);
  return f;
}

struct LampRun {
  int partAloneHands = 0;  ///< of kFrames frames with the part and no arm
  std::vector<Eigen::Vector2d> palms_px;
  std::vector<cv::Mat> masks;
};
constexpr int kFrames = 6;

LampRun run(const MarkerFreeHandDetector::Options& o, const Eigen::Vector3d& rgb) {
  MarkerFreeHandDetector detector(o);
  LampRun r;
  for (int i = 0; i < kBackgroundFrames; ++i) detector.detect(litFrame(i, std::nullopt, false, rgb));
  for (int i = 0; i < kFrames; ++i)  // the part placed, the hand gone
    if (detector.detect(litFrame(kBackgroundFrames + i, std::nullopt, true, rgb))) ++r.partAloneHands;
  for (int i = 0; i < kFrames; ++i) {
    const ArmPose arm{{260.0 + 10 * i, 200.0 + 5 * i}, (80.0 + 4.0 * i) * M_PI / 180, 0.06};
    const auto h = detector.detect(litFrame(kBackgroundFrames + kFrames + i, arm, true, rgb));
    r.palms_px.push_back(h ? h->palm_px : Eigen::Vector2d(-1e3, -1e3));
    r.masks.push_back(h ? detector.lastMask().clone() : cv::Mat());
  }
  return r;
}
}  // namespace lamp

TEST(MarkerFreeHandDetector, ShadedRedPartIsNoSkinUnderAWhiteOrAColdLamp) {
  using namespace lamp;
  const Eigen::Vector3d white(1.0, 1.0, 1.0), cold(0.85, 0.93, 1.0);
  const MarkerFreeHandDetector::Options defaults;
  ASSERT_GT(defaults.skinMaxChromaPerLuma, 0.0);
  const LampRun w = run(defaults, white), c = run(defaults, cold);
  EXPECT_EQ(w.partAloneHands, 0);
  EXPECT_EQ(c.partAloneHands, 0) << "the shaded red part is taken for a hand under the cold lamp";
  constexpr double kSameMask = 0.98;  // intersection over union of the hand masks under the two lamps
  for (int i = 0; i < kFrames; ++i) {
    ASSERT_FALSE(w.masks[i].empty()) << "frame " << i;
    ASSERT_FALSE(c.masks[i].empty()) << "frame " << i;
    EXPECT_LT((w.palms_px[i] - c.palms_px[i]).norm(), 1.0) << "frame " << i;
    const double iou = static_cast<double>(cv::countNonZero(w.masks[i] & c.masks[i])) /
                       std::max(1, cv::countNonZero(w.masks[i] | c.masks[i]));
    EXPECT_GT(iou, kSameMask) << "frame " << i;
  }
  MarkerFreeHandDetector::Options off = defaults;
  off.skinMaxChromaPerLuma = 0.0;
  EXPECT_EQ(run(off, cold).partAloneHands, kFrames) << "the scene should show the part as a hand without the rule";
  EXPECT_EQ(run(off, white).partAloneHands, kFrames) << "the scene should show the part as a hand without the rule";
}

TEST(MarkerFreeHandDetector, RejectsBadOptions) {
  MarkerFreeHandDetector::Options o;
  o.backgroundFrames = 0;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.skinMaxChromaPerLuma = -0.1;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.skinIlluminantNorm = -1.0;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.palmFromWrist_m = 0.0;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.palmFromFarEndAcrossRay_m = -0.12;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.skinLumaFloorFraction = 1.0;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.maxPalmSpeed_mps = -1.0;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.minWorkingWidth_px = 10;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.minSkinReach_m = -0.1;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.minBackgroundValidFraction = 1.5;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.backgroundFillDiameter_px = -1;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.palmHalfWidth_m = -0.04;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
  o = {};
  o.minPalmCrossSections = 2.0;
  EXPECT_THROW(MarkerFreeHandDetector{o}, core::InvalidInputError);
}

// ---- a real demonstrator -------------------------------------------------
// HRT1's task2 and task3 (datasets/real/hrt1-pick-place, MIT, credits in its
// README): a person beside a table, in view from the first frame, bare
// forearm, picks a plush toy up and drops it into a bin. The palm labels are
// our own, by eye (palm_labels.json). The whole recording is previewed (the
// whole-recording background and skin model), then every frame detected.
// SRP_HAND_DEBUG_DIR=<dir> writes every frame with the found and the
// labelled palm; SRP_HAND_OPTIONS=name=value,... overrides detector options (HandEvaluation.h).

/// `rate`: the share of labelled frames whose palm must lie within 40 px;
/// `maxError_px`: no palm farther from the label (none on the torso).
void checkRealTask(const std::string& task, double rate, double maxError_px) {
  const auto t = testing::loadHrt1(task);
  testing::PalmTiming timing;
  const char* debugDir = std::getenv("SRP_HAND_DEBUG_DIR");
  const auto errors = testing::palmErrors(t, testing::optionsFromEnvironment(), &timing, debugDir ? debugDir : "");
  std::printf("[ figures  ] %s: CPU preview %.1f ms/frame, first detect (background, skin model) %.0f ms, "
              "detect %.1f ms/frame over the other %zu frames\n",
              task.c_str(), timing.preview_ms_per_frame, timing.firstDetect_ms, timing.detect_ms_per_frame,
              t.frames.size() - 1);
  ASSERT_FALSE(errors.empty()) << task << ": no labelled frame";
  const double kRate = rate, kMaxError_px = maxError_px;
  std::printf("[ figures  ] %s: frame, palm u v, label u v, error px\n", task.c_str());
  for (const auto& e : errors)
    std::printf("[ figures  ] %s %2d %s %5.0f %5.0f  %5.0f %5.0f  %5.1f\n", task.c_str(), e.frame,
                e.detected ? (e.bareForearm ? "far-end" : "other  ") : "missed ", e.palm_px.x(), e.palm_px.y(),
                e.label_px.x(), e.label_px.y(), e.error_px);
  const auto s = testing::score(errors);
  std::printf("[ figures  ] %s: %d/%d frames within %.0f px (%.1f %%), median %.1f px, worst %.1f px\n", task.c_str(),
              s.within, s.labelled, testing::kPalmTol_px, 100.0 * s.rate(), s.median_px, s.worst_px);
  EXPECT_GE(s.within, kRate * static_cast<double>(s.labelled)) << task;
  EXPECT_LE(s.worst_px, kMaxError_px) << task;
}

// Both recordings are development data (all frames; task3 frames 0-8 were
// held out in session 6 and scored then). Issue 17's acceptance is >= 90 %
// within 40 px and no palm on the torso; the tests hold the level reached in
// session 7 (every frame within 40 px; the worst within a label's
// uncertainty, +-10 px, of the reached worst, far short of a hand length,
// ~90 px at 1.1 m, let alone the body).
TEST(MarkerFreeHandDetector, RealDemonstratorHrt1Task2) {
  constexpr double kTask2Rate = 1.0;        // reached 42/42 (acceptance 0.90)
  constexpr double kTask2Worst_px = 30.0;   // reached 18.7 px (session 8; 19.0 in session 7)
  checkRealTask("task2", kTask2Rate, kTask2Worst_px);
}

// task3: the arm alone in view, in shadow, entering through the band at the
// image's right edge that the depth camera does not see (frames 0-8).
TEST(MarkerFreeHandDetector, RealDemonstratorHrt1Task3) {
  constexpr double kTask3Rate = 1.0;        // reached 36/36 (acceptance 0.90)
  constexpr double kTask3Worst_px = 32.0;   // reached 17.9 px (session 8; 22.1 in session 7)
  checkRealTask("task3", kTask3Rate, kTask3Worst_px);
}

// ---- rendered synthetic demo ---------------------------------------------

// The first 150 frames: 1.5 s without the hand, the reach to the cuboid, the
// grasp (fingers closing) and the lift with the part in the hand.
constexpr int kFrames = 150;

/// Renders the default scene's demo of instruction 1 (`frames` < 0: whole).
void renderDemo(const std::string& rawlogPath, int frames, std::optional<std::uint32_t> seed) {
  const auto scene = core::Scene::load(std::string(SRP_SIM_DIR) + "/scenes/default.json");
  const auto catalogue = kb::loadCatalogue(scene.cataloguePath);
  synth::SynthDemoOptions o;
  o.demo.seed = seed.value_or(static_cast<std::uint32_t>(scene.seed));
  o.maxFrames = frames;
  synth::generateSyntheticDemo(scene, catalogue, synth::defaultPlanJson(), o, rawlogPath);
}

/// The demo to evaluate: SRP_HAND_DEMO (rendered whole first when missing,
/// with seed SRP_HAND_SEED or the scene's), else the first kFrames frames.
std::string demoToEvaluate() {
  if (const char* path = std::getenv("SRP_HAND_DEMO")) {
    if (!std::filesystem::exists(path)) {
      const char* seed = std::getenv("SRP_HAND_SEED");
      renderDemo(path, -1, seed ? std::optional<std::uint32_t>(std::stoul(seed)) : std::nullopt);
    }
    return path;
  }
  const std::string path = (std::filesystem::path(SRP_BINARY_DIR) / "perception_marker_free_hand.rawlog").string();
  renderDemo(path, kFrames, std::nullopt);
  return path;
}

TEST(MarkerFreeHandDetector, PalmCentreOnARenderedDemo) {
  const std::string demo = demoToEvaluate();
  std::string debugDir;
  std::FILE* csv = nullptr;
  if (const char* dir = std::getenv("SRP_HAND_DEBUG_DIR")) {
    std::filesystem::create_directories(debugDir = dir);
    csv = std::fopen((debugDir + "/geometry.csv").c_str(), "w");
    std::fprintf(csv, "frame,phase,grip,error_mm,have_wrist,along_err_mm,across_err_mm,z_err_mm,wrist_z_mm,x_mm,y_mm,z_mm,wrist_u\n");
  }
  const auto ev = testing::evaluateMarkerFreeHand(
      demo, testing::optionsFromEnvironment(),
      [&](const rawlog::RgbdFrame& f, const MarkerFreeHandDetector& d, const synth::GroundTruthFrame& truth,
          const std::optional<Eigen::Vector3d>& p_m) {
        if (debugDir.empty() || !p_m || !truth.handInView) return;
        const double e = (*p_m - truth.p_camera_palm_m).norm();
        // The error along and across the found axis and in depth [mm].
        const auto& g = d.lastGeometry();
        const Eigen::Vector3d de = *p_m - truth.p_camera_palm_m;
        std::fprintf(csv, "%d,%s,%.2f,%.1f,%d,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f\n", truth.index, truth.phase.c_str(),
                     truth.grip, 1e3 * e, g.haveWrist, 1e3 * de.head<2>().dot(g.axis),
                     1e3 * (g.axis.x() * de.y() - g.axis.y() * de.x()), 1e3 * de.z(), 0.0,
                     1e3 * truth.p_camera_palm_m.x(), 1e3 * truth.p_camera_palm_m.y(), 1e3 * truth.p_camera_palm_m.z(),
                     g.wrist_px.x());
        char name[80];
        std::snprintf(name, sizeof name, "/hand_%04d_%s_%03.0fmm.png", truth.index, truth.phase.c_str(), 1e3 * e);
        testing::drawHandGeometry(f, d, truth, debugDir + name);
      });
  if (csv) std::fclose(csv);
  ev.print(demo);
  ASSERT_GT(ev.handInView, 0);
  constexpr double kRate = 0.95;               // issue 5: detected in >= 95 % of the frames with the hand in view
  constexpr double kMedianTol_m = 0.015;       // issue 5: median palm error
  constexpr double kP95Tol_m = 0.040;          // not in the issue: guards the tail against regressions
  EXPECT_GE(ev.rate(), kRate);
  EXPECT_LE(ev.median_m(), kMedianTol_m);
  EXPECT_LE(ev.p95_m(), kP95Tol_m);
  EXPECT_EQ(ev.handWithoutHand, 0) << "a hand reported in frames without a hand";
}

}  // namespace
}  // namespace srp::perception
