// MarkerFreeHandDetector on HRT1's task2 and task3 (datasets/real/hrt1-pick-place,
// our palm labels) under label-preserving perturbations a new recording of
// the same kind plausibly brings (Hrt1Palms.h): the within-40-px rate and the
// worst error per perturbation, no new labels needed.
//
// SRP_HAND_OPTIONS="name=value,name=value" overrides detector options in
// every test here (the fields listed in optionsFromEnvironment), to select settings
// by leave-one-recording-out over recordings and perturbations:
//   SRP_HAND_OPTIONS=skinMaxMahalanobis=2.5 srp_perception_tests \
//     --gtest_filter='MarkerFreeHandRobustness.*'
// SRP_HAND_PERTURBATIONS='gain|JPEG' runs only the perturbations whose names
// contain one of these; SRP_HAND_TRACE_ERRORS=1 lists every frame outside
// 40 px; SRP_HAND_DEBUG_DIR=<dir> draws every frame, per perturbation.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

#include "HandEvaluation.h"
#include "Hrt1Palms.h"

namespace srp::perception {
namespace {

using testing::Hrt1Task;
using testing::PalmScore;

/// task2 and task3, read once per process.
const Hrt1Task& task(const std::string& name) {
  static std::map<std::string, Hrt1Task> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, testing::loadHrt1(name)).first;
  return it->second;
}

PalmScore scoreUnder(const std::string& name, const testing::Perturbation& p,
                     const MarkerFreeHandDetector::Options& o) {
  Hrt1Task t = task(name);  // a copy: the perturbation changes it
  for (auto& f : t.frames) {
    f.colour_bgr8 = f.colour_bgr8.clone();
    f.depth_m = f.depth_m.clone();
  }
  p.apply(t);
  const char* debug = std::getenv("SRP_HAND_DEBUG_DIR");  // every frame drawn, per perturbation
  std::string dir;
  if (debug) {
    dir = std::string(debug) + "/" + p.name;
    for (char& c : dir) if (c == ' ' || c == '(' || c == ')' || c == '%' || c == ',') c = '_';
  }
  const auto errors = testing::palmErrors(t, o, nullptr, dir);
  if (std::getenv("SRP_HAND_TRACE_ERRORS"))
    for (const auto& e : errors)
      if (!e.detected || e.error_px > testing::kPalmTol_px)
        std::printf("[ figures  ]   %s %s frame %d: %s %.1f px\n", p.name.c_str(), name.c_str(), e.frame,
                    e.detected ? "error" : "missed", e.error_px);
  return testing::score(errors);
}

/// Every perturbation on both recordings; prints the table. Returns the scores by (perturbation, task).
std::map<std::pair<std::string, std::string>, PalmScore> table(const MarkerFreeHandDetector::Options& o) {
  std::map<std::pair<std::string, std::string>, PalmScore> out;
  const char* only = std::getenv("SRP_HAND_PERTURBATIONS");  // substring filter (development)
  std::printf("[ figures  ] | perturbation | task2 within 40 px | worst px | task3 within 40 px | worst px |\n");
  int within = 0, labelled = 0;
  for (const auto& p : testing::hrt1Perturbations()) {
    if (only) {  // "a|b": names containing a or b
      bool keep = false;
      std::stringstream names(only);
      for (std::string part; std::getline(names, part, '|');) keep = keep || p.name.find(part) != std::string::npos;
      if (!keep) continue;
    }
    std::string row = "| " + p.name + " |";
    for (const std::string name : {"task2", "task3"}) {
      const PalmScore s = scoreUnder(name, p, o);
      out[{p.name, name}] = s;
      within += s.within;
      labelled += s.labelled;
      char cell[96];
      std::snprintf(cell, sizeof cell, " %d/%d%s | %.1f (median %.1f) |", s.within, s.labelled,
                    s.missed ? (" (" + std::to_string(s.missed) + " missed)").c_str() : "", s.worst_px, s.median_px);
      row += cell;
    }
    std::printf("[ figures  ] %s\n", row.c_str());
    std::fflush(stdout);
  }
  std::printf("[ figures  ] all perturbations: %d/%d within 40 px", within, labelled);
  for (const std::string name : {"task2", "task3"}) {
    int w = 0, n = 0;
    for (const auto& [key, s] : out)
      if (key.second == name) {
        w += s.within;
        n += s.labelled;
      }
    std::printf("; %s %d/%d", name.c_str(), w, n);
  }
  std::printf("\n");
  return out;
}

// Every perturbation on both recordings (the README's table). Asserted: the
// within-40-px rate under each perturbation a new recording from this camera
// plausibly brings (light, white balance, compression, noise, depth noise and
// random holes, the other intrinsics, a camera turned by a few degrees, the
// scene mirrored, half the frame rate, depth edge holes: 3 px on each side of
// every step of more than 5 cm, harsher than this camera's one-sided shadows):
// at least issue 17's 90 % on each recording; pooled over everything, the
// reached level. (Depth edge holes reached 35/42 before the background's
// sparse-depth pixels were filled from their neighbours,
// minBackgroundValidFraction: this test failed then.)
TEST(MarkerFreeHandRobustness, Hrt1UnderPerturbations) {
  constexpr double kMinRate = 0.90;        // issue 17's acceptance, per perturbation and recording
  constexpr double kMinPooledRate = 0.99;  // reached 1634/1638 = 99.8 % (with the gain 0.6 and the wires check rows)
  // No palm on the demonstrator's head or torso under any perturbation (the
  // gain 0.6 check included): in these recordings the head lies ~250-300 px
  // from the hand, the torso farther; reached worst 86.3 px (warm white
  // balance, task3 frame 17: on the toy, less than a hand length away).
  constexpr double kMaxPalmError_px = 120.0;
  const auto scores = table(testing::optionsFromEnvironment());
  int within = 0, labelled = 0;
  for (const auto& [key, s] : scores) {
    within += s.within;
    labelled += s.labelled;
    EXPECT_LE(s.worst_px, kMaxPalmError_px) << key.first << " on " << key.second << ": a palm off the hand";
    EXPECT_GE(s.rate(), kMinRate) << key.first << " on " << key.second << ": " << s.within << "/" << s.labelled;
  }
  ASSERT_GT(labelled, 0);
  EXPECT_GE(static_cast<double>(within) / labelled, kMinPooledRate) << within << "/" << labelled;
}

}  // namespace
}  // namespace srp::perception
