// The marker-free palm while the hand carries a part, seen from each viewpoint
// family of srp::synth (egocentric, side, top-down): no reported palm lies
// past the held part (beyond the part's origin on the line from the true
// palm in 3D, HandEvaluation.h), in any carry frame. Small renders (320x240, the
// whole two-part demonstration) keep it fast; the full-size figures are
// acceptance.perception.ViewpointFamilies.* (label slow).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "ViewpointDemos.h"

namespace srp::perception {
namespace {

/// The rawlog of `spec`, rendered once into the build folder.
std::string smallRender(const testing::ViewpointDemoSpec& spec) {
  return testing::renderViewpointDemo(spec, (std::filesystem::path(SRP_BINARY_DIR) / "viewpoint_demos_small").string());
}

/// `spec` rendered and scored as `srp perceive` runs the detector (`options`: the environment's).
testing::HandEvaluation scoreRender(const testing::ViewpointDemoSpec& spec,
                                    const MarkerFreeHandDetector::Options& options = testing::optionsFromEnvironment(),
                                    const std::string& what = "") {
  const auto ev = testing::evaluateMarkerFreeHand(smallRender(spec), options, {}, true);
  ev.print(spec.name() + what);
  return ev;
}

/// The small render of `spec` (variant 1, 320x240, seed 7), scored.
testing::HandEvaluation scoreSmallRender(testing::ViewpointDemoSpec& spec) {
  spec.variant = 1;
  spec.width_px = 320;
  spec.seed = 7;
  return scoreRender(spec);
}

/// An egocentric clip from a swaying head-mounted SR300-like sensor, 768x432 (its depth 256x192; MRPT's
/// renderer needs image widths that are multiples of 4), seed 7, the cuboid held in every frame.
testing::ViewpointDemoSpec headSr300Spec(int variant, double partScale, bool bareForearm) {
  testing::ViewpointDemoSpec spec;
  spec.family = synth::ViewpointFamily::Egocentric;
  spec.heldOnly = "cuboid";
  spec.bareForearm = bareForearm;
  spec.headSway = true;
  spec.sr300 = true;
  spec.width_px = 768;
  spec.variant = variant;
  spec.partScale = partScale;
  spec.seed = 7;
  return spec;
}

/// `maxPastFrames`: 0, except where the reached figure is guarded.
void expectNoPalmPastTheHeldPart(synth::ViewpointFamily family, double partScale, bool bareForearm,
                                 int maxPastFrames = 0) {
  testing::ViewpointDemoSpec spec;
  spec.family = family;
  spec.partScale = partScale;
  spec.bareForearm = bareForearm;
  const auto ev = scoreSmallRender(spec);
  ASSERT_GT(ev.carried, 0) << "the render shows no carry";
  EXPECT_LE(ev.farSide, maxPastFrames) << "palms past the held part; closest " << ev.worstFarSide_m << " m";
}

TEST(MarkerFreeHandViewpoints, NoPalmPastTheHeldPartEgocentric) {
  expectNoPalmPastTheHeldPart(synth::ViewpointFamily::Egocentric, 2.0, false);
  expectNoPalmPastTheHeldPart(synth::ViewpointFamily::Egocentric, 1.5, true);
}
// Side view: with the sleeve none; with a bare forearm not reached (the palm lands past the part in
// 16 of 144 carry frames), guarded at the reached count until that palm is placed right.
TEST(MarkerFreeHandViewpoints, PalmPastTheHeldPartSideGuarded) {
  expectNoPalmPastTheHeldPart(synth::ViewpointFamily::Side, 2.0, false);
  expectNoPalmPastTheHeldPart(synth::ViewpointFamily::Side, 1.5, true, 16);
}
// The side view's bare forearm (the small render PalmPastTheHeldPartSideGuarded scores): the preview
// that sees the arm as each frame does (holesInPreview), the skin learnt from the arm alone
// (skinFromArmOnly) and a hand no longer than a hand at the border placed from its fingertips
// (handFirstAtTheBorder) find the bare forearm, and no palm lands past the held part (off by default:
// the 320x240 egocentric bare clips lose, perception README).
TEST(MarkerFreeHandViewpoints, BareForearmFoundInThePreviewSide) {
  constexpr int kMaxPastFrames = 0;     // reached: 0 of 144 (16 with the options off)
  constexpr double kMinWithin = 0.50;   // reached: 51.8 % within 40 px (43.6 % off)
  constexpr int kMinPastFramesOff = 8;  // the options off: 16
  testing::ViewpointDemoSpec spec;
  spec.family = synth::ViewpointFamily::Side;
  spec.partScale = 1.5;
  spec.bareForearm = true;
  spec.variant = 1;
  spec.width_px = 320;
  spec.seed = 7;
  auto on = testing::optionsFromEnvironment();
  on.holesInPreview = on.skinFromArmOnly = on.handFirstAtTheBorder = true;
  const auto ev = scoreRender(spec, on, ", the arm's skin in the preview");
  ASSERT_GT(ev.carried, 0);
  EXPECT_LE(ev.farSide, kMaxPastFrames);
  EXPECT_GE(ev.within640(40.0), kMinWithin);
  auto off = on;
  off.holesInPreview = off.skinFromArmOnly = off.handFirstAtTheBorder = false;
  // The prior box's chroma bound alone also keeps the part's shaded face out of the skin here (0 past,
  // 60.7 %): off, to show what the three options do.
  off.skinMaxChromaPerLuma = 0.0;
  EXPECT_GE(scoreRender(spec, off, ", the preview by depth alone").farSide, kMinPastFramesOff);
}

TEST(MarkerFreeHandViewpoints, NoPalmPastTheHeldPartTopDown) {
  expectNoPalmPastTheHeldPart(synth::ViewpointFamily::TopDown, 2.0, false);
  expectNoPalmPastTheHeldPart(synth::ViewpointFamily::TopDown, 1.5, true);
}

/// A clip of a hand holding the part in every frame under a moving camera (`spec`, rendered): within
/// 40 px in at least `minWithin` of the frames, none past the part; at most `maxWithinBorderOnly` with
/// the arm entering through the image border only (enterThroughStillArm off).
void expectArmEntersThroughItsStillBackground(const testing::ViewpointDemoSpec& spec, double minWithin,
                                              double maxWithinBorderOnly) {
  constexpr double kWithin_px = 40.0;  // at 640-px width
  const auto ev = scoreRender(spec);
  ASSERT_GT(ev.carried, 0);
  EXPECT_EQ(ev.carried, ev.handInView) << "the hand holds the part in every frame";
  EXPECT_GE(ev.within640(kWithin_px), minWithin);
  EXPECT_EQ(ev.farSide, 0);
  auto borderOnly = testing::optionsFromEnvironment();
  borderOnly.enterThroughStillArm = false;
  const auto evBorderOnly = scoreRender(spec, borderOnly, ", the arm entering through the image border only");
  EXPECT_LE(evBorderOnly.within640(kWithin_px), maxWithinBorderOnly);
}

// A head-mounted camera that sways (synth::HeadSway), the hand holding the part in every frame: the
// whole-recording background follows the camera (followCameraMotion). A still camera's per-pixel
// background takes the swaying table for foreground and the palm lands far off.
TEST(MarkerFreeHandViewpoints, SwayingHeadCameraHandHoldingThePart) {
  constexpr double kWithin_px = 40.0;  // at 640-px width
  constexpr double kMinWithin = 0.94;  // reached: 94.4 % (68 of 72 frames)
  // The arm entering only through the image border (enterThroughStillArm off): 81.9 % (59 of 72): the
  // forearm, in every frame, is the background in the bottom rows and reaches no border there.
  constexpr double kMaxWithinBorderOnly = 0.9;
  constexpr double kMaxWithinStill = 0.2;  // a still camera's background: 0.0 %
  testing::ViewpointDemoSpec spec;
  spec.family = synth::ViewpointFamily::Egocentric;
  spec.heldOnly = "cuboid";
  spec.bareForearm = true;
  spec.headSway = true;
  spec.variant = 1;  // scoreSmallRender's clip
  spec.width_px = 320;
  spec.seed = 7;
  expectArmEntersThroughItsStillBackground(spec, kMinWithin, kMaxWithinBorderOnly);
  auto still = testing::optionsFromEnvironment();
  still.followCameraMotion = false;
  const auto evStill = scoreRender(spec, still, ", background of a still camera");
  EXPECT_LE(evStill.within640(kWithin_px), kMaxWithinStill);
}

// The held-out clip's kind of recording, small: a head-mounted SR300-like sensor (16:9 colour 768x432,
// depth 256x192 from its own camera, registered by `srp import`), swaying, a bare forearm holding the
// cuboid in every frame and entering at the bottom edge. The arm is in most of the background's samples
// where it enters, so the background there is the arm: the arm enters through the background standing
// above the table at the border (enterThroughStillArm). Variant 4's camera, the cuboid 1.5x, seed 7.
TEST(MarkerFreeHandViewpoints, HeadCameraArmInEveryFrameEntersThroughItsStillBackground) {
  constexpr double kMinWithin = 0.99;          // reached: 100 % (71 of 71 frames)
  constexpr double kMaxWithinBorderOnly = 0.97;  // the image border only: 94.4 % (67 of 71), 1 palm past the part
  const auto spec = headSr300Spec(4, 1.5, true);
  expectArmEntersThroughItsStillBackground(spec, kMinWithin, kMaxWithinBorderOnly);
}

// The same sensor with the demonstrator's sleeve (variant 2's camera, the cuboid 2x, seed 7): the depth
// camera, 25 mm beside the colour camera, does not see a band of the table beside the arm, and a depth
// hole is foreground by its colour. The moving camera's background colour is that of the samples showing
// the table there (backgroundColourFromSurface), not the mean with the arm that passed over it: else the
// band joins the hand (the table is of skin-like colour), the cuff is found on the band and the palm
// falls short of the hand. (At this size the rule also costs frames within 40 px: 79.2 % against 90.3 %
// with the mean colour; on the 1920x1080 family egocentric-held-sr300 it gains, perception README.)
TEST(MarkerFreeHandViewpoints, HeadCameraDepthShadowBesideTheArmIsNoHand) {
  constexpr double kMaxMedian_m = 0.035;            // reached: 29.5 mm
  constexpr double kMinMedianMeanColour_m = 0.045;  // the mean colour of every sample: 52.5 mm
  const auto spec = headSr300Spec(2, 2.0, false);
  const auto ev = scoreRender(spec);
  EXPECT_LE(ev.median_m(), kMaxMedian_m);
  EXPECT_EQ(ev.farSide, 0);
  auto meanColour = testing::optionsFromEnvironment();
  meanColour.backgroundColourFromSurface = false;
  const auto evMean = scoreRender(spec, meanColour, ", the background's colour the mean of every sample");
  EXPECT_GE(evMean.median_m(), kMinMedianMeanColour_m);
}

/// The palm's signed errors in the frames the cuff rule placed it [m]: along the true hand's axis (towards the
/// fingers) and along the camera's ray through the true palm (positive: too far).
struct CuffErrors {
  std::vector<double> alongAxis_m, alongRay_m;
};
CuffErrors cuffErrors(const std::string& rawlog, const MarkerFreeHandDetector::Options& options) {
  const auto gt = synth::DemoGroundTruth::load(synth::groundTruthPathFor(rawlog));
  CuffErrors out;
  testing::evaluateMarkerFreeHand(
      rawlog, options,
      [&](const rawlog::RgbdFrame&, const MarkerFreeHandDetector& d, const synth::GroundTruthFrame& truth,
          const std::optional<Eigen::Vector3d>& p_m) {
        if (!p_m || !truth.handInView || !d.lastGeometry().haveWrist) return;
        const Eigen::Vector3d axis_camera =
            gt.X_world_camera_at(truth.index).linear().transpose() * truth.X_world_hand.linear().col(0);
        out.alongAxis_m.push_back((*p_m - truth.p_camera_palm_m).dot(axis_camera));
        out.alongRay_m.push_back((*p_m - truth.p_camera_palm_m).dot(truth.p_camera_palm_m.normalized()));
      },
      true);
  return out;
}

/// A fresh render (seed 7, 320x240, variant 1, the sleeve), not one of the scored demonstrations.
std::string freshSleeveRender(synth::ViewpointFamily family) {
  testing::ViewpointDemoSpec spec;
  spec.family = family;
  spec.variant = 1;
  spec.width_px = 320;
  spec.seed = 7;
  return testing::renderViewpointDemo(spec, (std::filesystem::path(SRP_BINARY_DIR) / "viewpoint_demos_small").string());
}

// From the demonstrator's head the sleeve, thicker than the wrist, hides the wrist's first centimetres:
// the palm's length is measured from the sleeve's edge (cuffAtSleeveEdge), not from the first skin seen
// (which puts the palm ~15 mm towards the fingers). A fresh render (seed 7, 320x240), not the scored ones.
TEST(MarkerFreeHandViewpoints, CuffFromTheSleeveEdgeEgocentric) {
  const std::string rawlog = freshSleeveRender(synth::ViewpointFamily::Egocentric);
  constexpr double kAlongAxisTol_m = 0.006;  // the hand model's cuff-to-palm length is known to a few mm
  MarkerFreeHandDetector::Options o = testing::optionsFromEnvironment();
  o.palmHalfWidth_m = 0.0;  // this rule alone (the silhouette's depth moves the palm along the ray)
  o.cuffAtSleeveEdge = true;
  const auto along = cuffErrors(rawlog, o).alongAxis_m;
  ASSERT_GT(along.size(), 100u) << "too few frames with the cuff in view";
  std::printf("[ figures  ] along the hand's axis, cuff rule, from the sleeve's edge: median %+.1f mm (%zu frames)\n",
              1e3 * testing::percentile(along, 0.5), along.size());
  EXPECT_NEAR(testing::percentile(along, 0.5), 0.0, kAlongAxisTol_m);
  o.cuffAtSleeveEdge = false;
  const auto fromSkin = cuffErrors(rawlog, o).alongAxis_m;
  std::printf("[ figures  ] the same from the first skin: median %+.1f mm\n", 1e3 * testing::percentile(fromSkin, 0.5));
  EXPECT_GT(testing::percentile(fromSkin, 0.5), kAlongAxisTol_m) << "the hidden wrist no longer shifts the palm";
}

// From the side the camera sees the hand's edge: its silhouette is narrower than the palm, and the palm
// centre lies deeper behind the surface than half the palm's thickness (palmHalfWidth_m, an elliptic
// cross-section of the hand model's width and thickness, srp::synth's glove's 42 mm by default).
TEST(MarkerFreeHandViewpoints, PalmDepthFromTheSilhouetteSide) {
  const std::string rawlog = freshSleeveRender(synth::ViewpointFamily::Side);
  // The glove's cross-section is a box with a thumb, deeper behind its edge than the ellipse says.
  constexpr double kAlongRayTol_m = 0.020;
  MarkerFreeHandDetector::Options o = testing::optionsFromEnvironment();
  const auto ray = cuffErrors(rawlog, o).alongRay_m;
  ASSERT_GT(ray.size(), 100u) << "too few frames with the cuff in view";
  std::printf("[ figures  ] along the ray, cuff rule, side: median %+.1f mm (%zu frames)\n",
              1e3 * testing::percentile(ray, 0.5), ray.size());
  EXPECT_NEAR(testing::percentile(ray, 0.5), 0.0, kAlongRayTol_m);
  o.palmHalfWidth_m = 0.0;
  const auto underBack = cuffErrors(rawlog, o).alongRay_m;
  std::printf("[ figures  ] the same at half the palm's thickness: median %+.1f mm\n",
              1e3 * testing::percentile(underBack, 0.5));
  EXPECT_LT(testing::percentile(underBack, 0.5), -kAlongRayTol_m) << "the palm's edge no longer hides its depth";
}

}  // namespace
}  // namespace srp::perception
