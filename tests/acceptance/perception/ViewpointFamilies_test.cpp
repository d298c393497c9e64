// The marker-free palm on rendered demonstrations from eight viewpoint
// families (srp::synth Viewpoint.h), the hand carrying parts of three sizes,
// with the demonstrator's sleeve and with a bare forearm, against the
// render's ground truth (HandEvaluation.h), through the preview as `srp
// perceive` runs the detector.
//
// The detector's settings are chosen on the egocentric and side families
// (their frames are looked at to find what fails); top-down, front,
// oblique, near-corner and table-level are only checked, never looked at frame by frame nor tuned on
// (perception README). Each
// family's reached figures are guarded (the acceptance is not reached). Near-corner
// and table-level are lit by another lamp than the scene's (ViewpointDemos.h's WarmLight: warm, from the
// robot's side at 40 deg); their renders' geometry is tested by ViewpointFamilyRenders.* (no detector).
//
// A development family, facing: across the table from the demonstrator, lower than front and 30-45 deg off
// their direction, lit by a cold lamp from the demonstrator's side (ViewpointDemos.h's ColdLight); chosen on
// (its frames may be looked at), seeds 11-16 (SRP_VIEW_FIRST_SEED=17 renders seeds 17-22, also development).
//
// A sixth, development family, egocentric-held: an egocentric head-mounted camera that sways
// (synth::HeadSway), the hand holding a part in every frame (the clip cut from grasp to release),
// bare forearm and sleeve, parts of several sizes. Its seeds 41-46 are chosen on, 51-56 checked.
// Its variants egocentric-held-wired and egocentric-held-sr300-wired dress the hand with sensor wires and
// tape (ViewpointDemoSpec::sensorWires; seeds 41-46, chosen on).
//
// SRP_VIEW_DIR=<dir> keeps the renders there (default: rendered into the build folder and deleted once scored);
// SRP_VIEW_FAMILY=egocentric|side|top-down|front|oblique|near-corner|table-level|facing|egocentric-held|
// egocentric-held-sr300|egocentric-held-wired|egocentric-held-sr300-wired runs one family; SRP_VIEW_VARIANT=0..5 one
// of its demonstrations;
// SRP_VIEW_WIDTH=px renders at another width (4:3; the figures stay at 640-px width: a check that the detector's
// pixel options scale, as a 1920-px recording needs);
// SRP_HAND_DEBUG_DIR=<dir> draws every hand frame with the found geometry;
// SRP_HAND_OPTIONS=name=value,... overrides detector options (HandEvaluation.h);
// SRP_VIEW_PHASES=grasp,move,... previews and scores only the frames of these phases (idle, reach, grasp, move,
// release, retract): e.g. grasp alone is a recording with the hand in view and nearly still in every frame (the
// guarded figures then fail: they are for the whole demonstrations);
// SRP_HAND_CSV=<file> writes one row per hand-in-view frame (the palm's error in the camera frame, the
// true hand's axis and normal, the rule that placed the palm, how far past the held part it lies, the detector's
// anchor, hand axis, back normal and walked length) for
// decompositions of the error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "ViewpointDemos.h"

namespace srp::perception {
namespace {

using testing::ViewpointDemoSpec;

/// Six demonstrations per family (ViewpointDemos.h's familySpecs), at SRP_VIEW_WIDTH when set; the
/// development family facing from SRP_VIEW_FIRST_SEED when set (seeds 11-16 otherwise).
std::vector<ViewpointDemoSpec> familySpecs(synth::ViewpointFamily family) {
  const char* width = std::getenv("SRP_VIEW_WIDTH");
  const char* firstSeed = std::getenv("SRP_VIEW_FIRST_SEED");
  const bool otherSeeds = firstSeed && family == synth::ViewpointFamily::Facing;
  return testing::familySpecs(family, width ? std::atoi(width) : 640,
                              otherSeeds ? static_cast<std::uint32_t>(std::atoi(firstSeed)) : 11u);
}

/// The egocentric-held family: variants 0-5 of the egocentric viewpoint, head sway, the cuboid (even
/// variants) or the parallelogram (odd) held from grasp to release, parts 1x, 1.5x and 2x the catalogue's
/// (the parallelogram at most 1.5x: larger leaves it no room in the gray box), sleeve in 0-2, bare
/// forearm in 3-5; seeds `firstSeed` + variant.
std::vector<ViewpointDemoSpec> heldSwaySpecs(std::uint32_t firstSeed, bool sr300 = false, bool sensorWires = false) {
  std::vector<ViewpointDemoSpec> out;
  constexpr double kScales[] = {1.0, 1.5, 2.0};
  for (int v = 0; v < 6; ++v) {
    ViewpointDemoSpec s;
    s.family = synth::ViewpointFamily::Egocentric;
    s.variant = v;
    s.heldOnly = v % 2 == 0 ? "cuboid" : "parallelogram";
    s.partScale = s.heldOnly == "parallelogram" ? std::min(1.5, kScales[v % 3]) : kScales[v % 3];
    s.bareForearm = v >= 3;
    s.headSway = true;
    s.seed = firstSeed + static_cast<std::uint32_t>(v);
    s.sensorWires = sensorWires;
    if (sr300) {
      s.sr300 = true;
      s.width_px = 1920;
    }
    out.push_back(s);
  }
  return out;
}
constexpr std::uint32_t kHeldChooseSeed = 41, kHeldCheckSeed = 51;

testing::HandEvaluation evaluateSpecs(const std::vector<ViewpointDemoSpec>& specs, const std::string& what) {
  const char* dir = std::getenv("SRP_VIEW_DIR");
  const std::string folder = dir ? dir : (std::filesystem::path(SRP_BINARY_DIR) / "viewpoint_demos").string();
  const char* debug = std::getenv("SRP_HAND_DEBUG_DIR");
  const char* variant = std::getenv("SRP_VIEW_VARIANT");
  testing::HandEvaluation pooled;
  const char* csvPath = std::getenv("SRP_HAND_CSV");
  std::ofstream csv;
  if (csvPath) {
    csv.open(csvPath);
    csv << "demo,frame,phase,grip,carry,detected,rule,depth_carried,x,y,z,tx,ty,tz,ax,ay,az,nx,ny,nz,past_m,"
           "ex,ey,ez,ux,uy,uz,qx,qy,qz,d_m\n";
  }
  for (const auto& spec : specs) {
    if (variant && std::atoi(variant) != spec.variant) continue;
    const std::string rawlog = testing::renderViewpointDemo(spec, folder);
    std::string debugDir;
    if (debug) std::filesystem::create_directories(debugDir = std::string(debug) + "/" + spec.name());
    double lastZ_m = -1.0;
    const synth::DemoGroundTruth gt =
        csvPath ? synth::DemoGroundTruth::load(synth::groundTruthPathFor(rawlog)) : synth::DemoGroundTruth{};
    const auto ev = testing::evaluateMarkerFreeHand(
        rawlog, testing::optionsFromEnvironment(),
        [&](const rawlog::RgbdFrame& f, const MarkerFreeHandDetector& d, const synth::GroundTruthFrame& truth,
            const std::optional<Eigen::Vector3d>& p_m) {
          if (csvPath && truth.handInView) {
            // The hand's axis (towards the fingers) and back normal in the camera frame.
            const Eigen::Matrix3d R = gt.X_world_camera_at(truth.index).linear().transpose() * truth.X_world_hand.linear();
            const auto& g = d.lastGeometry();
            // A depth carried from an earlier frame repeats that frame's depth exactly.
            const bool carriedDepth = p_m && p_m->z() == lastZ_m;
            const Eigen::Vector3d p = p_m.value_or(Eigen::Vector3d::Zero()), t = truth.p_camera_palm_m;
            // How far the palm lies past the held part's origin (HandEvaluation::farSide: > 0 is past it).
            double past_m = std::nan("");
            if (p_m && !truth.carriedObject.empty()) {
              const Eigen::Vector3d toPart = gt.X_camera_object(truth.index, truth.carriedObject).translation() - t;
              past_m = (p - t).dot(toPart.normalized()) - toPart.norm();
            }
            csv << spec.name() << ',' << truth.index << ',' << truth.phase << ',' << truth.grip << ','
                << !truth.carriedObject.empty() << ',' << p_m.has_value() << ','
                << (!p_m ? "none" : g.bareForearm ? "far_end" : g.haveWrist ? "cuff" : "fingertips") << ','
                << carriedDepth << ',' << p.x() << ',' << p.y() << ',' << p.z() << ',' << t.x() << ',' << t.y() << ','
                << t.z() << ',' << R(0, 0) << ',' << R(1, 0) << ',' << R(2, 0) << ',' << R(0, 2) << ',' << R(1, 2)
                << ',' << R(2, 2) << ',' << past_m;
            // The detector's anchor, hand axis and back normal (camera frame) and the length walked.
            for (const auto* v : {&g.anchor_camera_m, &g.axis_camera, &g.normal_camera})
              csv << ',' << v->x() << ',' << v->y() << ',' << v->z();
            csv << ',' << g.palmFromAnchor_m << '\n';
          }
          if (p_m) lastZ_m = p_m->z();
          if (debugDir.empty() || (!truth.handInView && !p_m)) return;
          char name[96];
          std::snprintf(name, sizeof name, "/hand_%04d_%s_%s%03.0fmm.png", truth.index, truth.phase.c_str(),
                        !truth.handInView             ? "nohand_"
                        : truth.carriedObject.empty() ? ""
                                                      : "carry_",
                        p_m ? 1e3 * (*p_m - truth.p_camera_palm_m).norm() : 999.0);
          testing::drawHandGeometry(f, d, truth, debugDir + name);
        },
        true);
    ev.print(spec.name());
    pooled.add(ev);
    if (!dir) {  // ~100 MB per render: kept only where SRP_VIEW_DIR asks for it
      std::filesystem::remove(rawlog);
      std::filesystem::remove(synth::groundTruthPathFor(rawlog));
    }
  }
  pooled.print(what + ", pooled");
  return pooled;
}

testing::HandEvaluation evaluateFamily(synth::ViewpointFamily family) {
  return evaluateSpecs(familySpecs(family), synth::viewpointFamilyName(family));
}

bool selected(const std::string& family) {
  const char* only = std::getenv("SRP_VIEW_FAMILY");
  return !only || only == family;
}
bool selected(synth::ViewpointFamily family) { return selected(synth::viewpointFamilyName(family)); }

constexpr double kWithin_px = 40.0;  // issue 37: at 640-px width

/// What a family must reach: issue 37 asks, on the checked families, for a palm median <= 15 mm,
/// >= 95 % of the hand-in-view frames within kWithin_px and no palm past the held part. Not reached
/// yet (perception README); these bounds guard the reached figures.
struct Reached {
  double median_m, withinRate;
  int maxFarSide;
  int maxHandWithoutHand = 0;  ///< frames without a hand in which a hand is reported
};

void checkEvaluation(const testing::HandEvaluation& ev, const Reached& reached) {
  ASSERT_GT(ev.handInView, 0);
  EXPECT_LE(ev.median_m(), reached.median_m);
  EXPECT_GE(ev.within640(kWithin_px), reached.withinRate);
  EXPECT_LE(ev.farSide, reached.maxFarSide) << "palms past the held part";
  EXPECT_LE(ev.handWithoutHand, reached.maxHandWithoutHand) << "a hand reported in frames without a hand";
}

void checkFamily(synth::ViewpointFamily family, const Reached& reached) {
  if (!selected(family)) GTEST_SKIP() << "SRP_VIEW_FAMILY selects another family";
  checkEvaluation(evaluateFamily(family), reached);
}

void checkHeldSway(std::uint32_t firstSeed, const Reached& reached, bool sr300 = false, bool sensorWires = false) {
  const std::string family =
      std::string(sr300 ? "egocentric-held-sr300" : "egocentric-held") + (sensorWires ? "-wired" : "");
  if (!selected(family)) GTEST_SKIP() << "SRP_VIEW_FAMILY selects another family";
  checkEvaluation(evaluateSpecs(heldSwaySpecs(firstSeed, sr300, sensorWires),
                                family + " seeds " + std::to_string(firstSeed) + "+"),
                  reached);
}

// Reached: 95.2 %, 10.6 mm, 0 past the part (chosen on).
TEST(ViewpointFamilies, EgocentricChosenOn) { checkFamily(synth::ViewpointFamily::Egocentric, {0.011, 0.95, 0}); }
// Reached: 77.5 %, 23.3 mm, 0 of 653 carry frames past the part (chosen on).
TEST(ViewpointFamilies, SideChosenOn) { checkFamily(synth::ViewpointFamily::Side, {0.024, 0.77, 0}); }
// Reached: 86.2 %, 4.3 mm, 0 of 653 carry frames past the part.
TEST(ViewpointFamilies, TopDownChecked) { checkFamily(synth::ViewpointFamily::TopDown, {0.0045, 0.86, 0}); }
// Reached: 88.2 %, 38.7 mm, 2 of 657 carry frames past the part (closest 20 mm).
TEST(ViewpointFamilies, FrontChecked) { checkFamily(synth::ViewpointFamily::Front, {0.039, 0.88, 2}); }
// Reached: 83.5 %, 21.9 mm, 0 of 653 carry frames past the part (skinMaxChromaPerLuma=0: 81.1 %, 20.6 mm).
TEST(ViewpointFamilies, ObliqueChecked) { checkFamily(synth::ViewpointFamily::Oblique, {0.022, 0.83, 0}); }
// Check families under another light than the scene's (warm, from the robot's side), scored once and never
// tuned on. Reached: 82.8 %, 26.7 mm, 0 of 652 carry frames past the part, no hand in a frame without one.
TEST(ViewpointFamilies, NearCornerChecked) { checkFamily(synth::ViewpointFamily::NearCorner, {0.027, 0.82, 0, 0}); }
// Reached: 78.7 %, 25.2 mm, 0 of 653 carry frames past the part.
TEST(ViewpointFamilies, TableLevelChecked) { checkFamily(synth::ViewpointFamily::TableLevel, {0.026, 0.78, 0}); }
// Development family facing (cold light from the demonstrator's side), seeds 11-16, chosen on.
// Reached: 77.1 %, 36.3 mm, 0 of 656 carry frames past the part, no hand in a frame without one
// (skinMaxChromaPerLuma=0: 79.7 %, 35.0 mm, 1 past, a hand in 118 frames without one).
TEST(ViewpointFamilies, FacingChosenOn) { checkFamily(synth::ViewpointFamily::Facing, {0.0365, 0.77, 0, 0}); }
// Development family egocentric-held (head sway, the part held in every frame).
// Reached on the seeds chosen on: 99.7 %, 8.7 mm, 0 of 394 carry frames past the part (the arm entering
// through the image border only: 91.6 %, 10.3 mm; a still camera's background: 0.0 %, 425.8 mm, 135 past).
TEST(ViewpointFamilies, EgocentricHeldSwayChosenOn) { checkHeldSway(kHeldChooseSeed, {0.0095, 0.99, 0}); }
// Reached on the seeds checked: 100.0 %, 8.5 mm, 0 of 396 (before this detector's moving-camera arm, gap and
// colour rules: 97.7 %, 8.6 mm; a still camera's background: 0.3 %, 482.8 mm, 177 past).
TEST(ViewpointFamilies, EgocentricHeldSwayChecked) { checkHeldSway(kHeldCheckSeed, {0.009, 0.99, 0}); }
// Development family egocentric-held-sr300: the same clips (seeds 41-46, chosen on) recorded as the
// held-out clip's sensor records them (ViewpointDemoSpec::sr300: colour 1920x1080, depth 640x480 from its
// own camera, registered by `srp import`), scored at 640-px width.
// Reached, worked on at 960x540 (minWorkingWidth_px): 99.2 %, 10.2 mm, 0 of 393 carry frames past the part
// (at 1920x1080: 96.7 %, 10.0 mm, 0 past; without enterThroughStillArm, movingBackgroundGap and
// backgroundColourFromSurface: 74.6 %, 25.3 mm, 0 past).
TEST(ViewpointFamilies, EgocentricHeldSwaySr300ChosenOn) { checkHeldSway(kHeldChooseSeed, {0.011, 0.99, 0}, true); }
// The same clips on the seeds checked (51-56), scored once. Reached: 89.9 %, 11.3 mm, 0 of 397 past the part
// (at 1920x1080: 79.1 %, 11.0 mm, 34 past, all in v3).
TEST(ViewpointFamilies, EgocentricHeldSwaySr300Checked) { checkHeldSway(kHeldCheckSeed, {0.012, 0.89, 0}, true); }
// Development variants egocentric-held-wired and egocentric-held-sr300-wired: the same clips (seeds 41-46,
// chosen on) with the hand dressed as a glove-less sensor rig (ViewpointDemoSpec::sensorWires: 2 mm dark
// wires along the back of the digits and the hand, 12 mm white tape on the fingertips and the back of
// the hand, an 18 mm band of tape at the wrist). The dressing breaks the default detector (the wires and the
// band cut the skin into narrow pieces); skinGapClose_m=0.02 closes them (off by default: on facing it joins
// an open hand's fingers across the held part, 76.4 % and 15 palms past it against 79.7 % and 1; at 0.012 m
// 77.5 % and 6; perception README).
// Reached: 72.6 %, 73.6 mm, 0 of 394 carry frames past the part (skinGapClose_m=0.02: 99.5 %, 11.2 mm, 0).
TEST(ViewpointFamilies, EgocentricHeldSwayWiredChosenOn) { checkHeldSway(kHeldChooseSeed, {0.075, 0.72, 0}, false, true); }
// Reached, worked on at 960x540: 85.0 %, 65.7 mm, 0 of 393 carry frames past the part (at 1920x1080: 88.8 %,
// 67.9 mm; with skinGapClose_m=0.02 at 1920x1080: 97.7 %, 10.1 mm, 1 past).
TEST(ViewpointFamilies, EgocentricHeldSwaySr300WiredChosenOn) {
  checkHeldSway(kHeldChooseSeed, {0.068, 0.83, 0}, true, true);
}

}  // namespace
}  // namespace srp::perception
