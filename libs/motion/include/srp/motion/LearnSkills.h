#pragma once
/// \file LearnSkills.h
/// \brief The Motion module in one call: a demonstration's hand and object
/// tracks -> segmentation (Segmenter) -> one SkillSet per moved object
/// (SkillLearner). `srp program`, `srp motion`, the execution notebook and the
/// tests all learn skills through this function.
///
/// \code
///   srp::motion::DemoTracks demo{hand, objects, {"cuboid", "star"}};
///   const srp::motion::LearnedSkills learned = srp::motion::learnSkills(demo);
///   // learned.segmentation.objects[i].graspFrame, learned.skills[i].reach
/// \endcode

#include <string>
#include <vector>

#include "srp/core/PositionTrajectory.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/SkillLearner.h"
#include "srp/motion/SkillSet.h"

namespace srp::motion {

/// What segmentation needs of a demonstration: the hand and the plan objects'
/// tracks (the same frames, camera frame, metres) and the plan order (one
/// object name per step; the tracks are keyed by the same names).
struct DemoTracks {
  core::PositionTrajectory hand;
  std::vector<ObjectTrack> objects;
  std::vector<std::string> planOrder;
};

/// The segmentation and the skills learned from it.
struct LearnedSkills {
  Segmentation segmentation;
  std::vector<SkillSet> skills;  ///< one per moved object, plan order
};

/// Segments the demonstration and learns the skills. Throws InvalidInputError
/// as Segmenter::segment and SkillLearner::learn do (nothing is returned).
LearnedSkills learnSkills(const DemoTracks& demo, const Segmenter& segmenter = Segmenter(),
                          const SkillLearner& learner = SkillLearner());

}  // namespace srp::motion
