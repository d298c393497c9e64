#include "srp/motion/LearnSkills.h"

namespace srp::motion {

LearnedSkills learnSkills(const DemoTracks& demo, const Segmenter& segmenter, const SkillLearner& learner) {
  LearnedSkills out;
  out.segmentation = segmenter.segment(demo.hand, demo.objects, demo.planOrder);
  out.skills = learner.learn(out.segmentation, demo.objects);
  return out;
}

}  // namespace srp::motion
