#pragma once
/// \file SkillPlots.h
/// \brief PNG figures of one object's segmentation and learned skills, like the
/// thesis' fig. 8.5 (object trajectory coloured by mixture component, grasp
/// and release marked) and figs. 8.6/8.7 (demo, reproduction and adaptation
/// of the Reach and Move DMPs).

#include <string>

#include "srp/motion/Segmenter.h"
#include "srp/motion/SkillSet.h"

namespace srp::motion {

/// Shift of start and goal of the adaptation shown (the reference README's).
struct AdaptationShift {
  Eigen::Vector3d start_m{0.05, -0.03, 0.02};
  Eigen::Vector3d goal_m{-0.04, 0.06, -0.01};
};

/// Writes a 2 x 2 figure: object x/y/z over time by mixture component with
/// grasp/release lines; hand distance to the object's initial position;
/// Reach and Move: demo, reproduction, adaptation per axis. Throws FileError.
void writeSkillFigure(const std::string& pngPath, const Segmentation& segmentation,
                      const ObjectSegmentation& object, const SkillSet& skills, const AdaptationShift& shift = {});

}  // namespace srp::motion
