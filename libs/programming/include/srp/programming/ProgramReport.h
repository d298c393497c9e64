#pragma once
/// \file ProgramReport.h
/// \brief The report folder of `srp program`: PNG figures like the thesis'
/// fig. 8.3 (hand trajectory), 8.5 (segmentation) and 8.6-8.8 (DMPs), and a
/// short Markdown summary linking them.

#include <string>
#include <vector>

#include "srp/motion/Segmenter.h"
#include "srp/motion/SkillSet.h"
#include "srp/perception/DemoPerception.h"
#include "srp/programming/ProgrammingPipeline.h"

namespace srp::programming {

/// Writes `dir`/hand_trajectory.png, one `<object>_skills.png` per moved
/// object and `summary.md`; returns the paths written. Creates `dir`.
std::vector<std::string> writeProgramReport(const std::string& dir, const ProgramResult& result,
                                            const perception::PerceptionResult& seen,
                                            const motion::Segmentation& segmentation,
                                            const std::vector<motion::SkillSet>& skills);

/// The hand trajectory figure alone (x, y, z over time with detections
/// marked, and the top view with grasp/release points).
void writeHandFigure(const std::string& pngPath, const perception::PerceptionResult& seen,
                     const motion::Segmentation& segmentation);

}  // namespace srp::programming
