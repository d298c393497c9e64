#pragma once
// Noise-free labelled demos from the synthetic-demo module's choreography
// (libs/synth planDemonstration: the thesis' default scene and instruction 1,
// the choreography the rendered demos use) and the error tables of the
// real-track noise tests.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <iostream>

#include "srp/motion/RealTrackNoise.h"
#include "srp/motion/Segmenter.h"
#include "srp/synth/LabelledDemo.h"

namespace srp::motion::testing {

/// The synth module's choreography as noise-free labelled tracks (libs/synth LabelledDemo.h).
inline LabelledDemo cleanSynthDemo(std::uint32_t seed) { return synth::cleanLabelledDemo(seed); }

/// Which real recording's behaviours the noise model adds.
enum class Recording {
  First,  ///< outliers, hand jumps, lingering and nudges (RealTrackNoise::Options::placement off)
  Both,   ///< also the second one's placement behaviours: hover, hidden parts, ghosts (the default)
};

/// The tracks a segmenter sees (plan objects first, then the others, like a perception CSV).
inline RealTrackNoise::Result noisySynthDemo(std::uint32_t seed, Recording recording = Recording::Both) {
  RealTrackNoise::Options c;
  c.seed = seed;
  c.placement = recording == Recording::Both;
  return RealTrackNoise(c).apply(cleanSynthDemo(seed));
}

struct EventErrors {
  std::vector<int> grasp, release;  // estimate - truth, frames
  int demos = 0;                    // demos evaluated
  int within(int tol) const {
    int k = 0;
    for (int e : grasp) k += std::abs(e) <= tol;
    for (int e : release) k += std::abs(e) <= tol;
    return k;
  }
  int count() const { return static_cast<int>(grasp.size() + release.size()); }
  int worst() const {
    int w = 0;
    for (int e : grasp) w = std::max(w, std::abs(e));
    for (int e : release) w = std::max(w, std::abs(e));
    return w;
  }
};

}  // namespace srp::motion::testing

namespace srp::motion::testing {

/// The noisy synth demos of `seeds` (a seed for which the synth planner finds
/// no free spot is not a demo and is left out).
struct NoisyDemo {
  std::uint32_t seed = 0;
  RealTrackNoise::Result result;
};
inline std::vector<NoisyDemo> noisyDemos(const std::vector<std::uint32_t>& seeds, Recording recording) {
  std::vector<NoisyDemo> demos;
  for (std::uint32_t seed : seeds) {
    try {
      demos.push_back({seed, noisySynthDemo(seed, recording)});
    } catch (const std::exception&) {
    }
  }
  return demos;
}

/// Grasp/release errors of `config` on `demos` (printed per event when `print`).
inline EventErrors evaluateNoisy(const std::vector<NoisyDemo>& demos, const Segmenter::Options& config,
                                 const std::string& label, bool print) {
  EventErrors errors;
  for (const auto& [seed, r] : demos) {
    ++errors.demos;
    const auto seg = Segmenter(config).segment(r.noisy.hand, r.noisy.objects, r.noisy.planOrder);
    for (std::size_t k = 0; k < r.noisy.planOrder.size(); ++k) {
      const auto& o = seg.objects[k];
      const int g = o.moved ? o.graspIndex - r.truth.graspIndex[k] : 9999;
      const int rel = o.moved ? o.releaseIndex - r.truth.releaseIndex[k] : 9999;
      errors.grasp.push_back(g);
      errors.release.push_back(rel);
      if (print)
        std::cout << label << " seed " << seed << " " << o.name << ": grasp " << g << ", release " << rel
                  << " [outliers " << o.outlierFraction << ", margin " << o.releaseMargin << ", gap " << o.releaseCueGap
                  << (o.lowConfidence ? ", low]" : "]")
                  << (r.nudgeIndex[k] >= 0 ? " (nudged)" : "") << (r.ghostOf[k] >= 0 ? " (ghost)" : "")
                  << (r.pauseKept[k] ? "" : " (no pause)") << "\n";
    }
  }
  return errors;
}

inline std::vector<std::uint32_t> seedRange(std::uint32_t from, std::uint32_t count) {
  std::vector<std::uint32_t> s;
  for (std::uint32_t i = 0; i < count; ++i) s.push_back(from + i);
  return s;
}

}  // namespace srp::motion::testing
