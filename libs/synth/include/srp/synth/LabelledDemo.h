#pragma once
/// \file LabelledDemo.h
/// \brief The synthetic demonstration's choreography (planDemonstration of
/// the default scene and instruction 1, the demos `srp synth-demo` renders)
/// as noise-free labelled tracks for the segmenter: what `srp segment
/// --noise real` and the real-track noise tests start from.

#include <cstdint>

#include "srp/motion/RealTrackNoise.h"

namespace srp::synth {

/// Palm and object positions in the camera frame (hand invalid, zeros, while
/// idle out of view; every scene object tracked, yaw per sample); truth = the
/// timeline's events (grasp = first frame the object moves with the hand,
/// release = the last). Throws as planDemonstration does.
motion::LabelledDemo cleanLabelledDemo(std::uint32_t seed);

}  // namespace srp::synth
