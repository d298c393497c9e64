// The programming tests' small, fast synthetic demo: 320x240, short idles, a
// brisk demonstrator (about 2 s of frames per pick & place).
#pragma once

#include <cstdint>

#include "srp/synth/DemoGenerator.h"

namespace srp::programming::test {

inline synth::SynthDemoOptions smallDemoOptions(std::uint32_t seed) {
  synth::SynthDemoOptions opt;
  opt.width_px = 320;
  opt.height_px = 240;
  opt.demo.seed = seed;
  opt.demo.idleStart_s = 0.7;
  opt.demo.idleEnd_s = 0.7;
  opt.demo.speedFactor = 1.4;
  return opt;
}

}  // namespace srp::programming::test
