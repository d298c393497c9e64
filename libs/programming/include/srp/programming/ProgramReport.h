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
#include "srp/programming/ProgramResult.h"
#include "srp/programming/ProgrammingOptions.h"
#include "srp/taskdb/Rows.h"

namespace srp::programming {

/// Writes `dir`/hand_trajectory.png, one `<object>_skills.png` per moved
/// object and `summary.md`; returns the paths written. Creates `dir`.
std::vector<std::string> writeProgramReport(const std::string& dir, const ProgramResult& result,
                                            const perception::PerceptionResult& seen,
                                            const motion::Segmentation& segmentation,
                                            const std::vector<motion::SkillSet>& skills);

/// Frames evenly spread over the recording on a program report's contact sheet
/// (besides each moved object's grasp and release frames).
inline constexpr int kContactSheetSpreadFrames = 8;

/// `dir`/contact_sheet.png: what perception saw, drawn on the demonstration
/// (read again from ProgrammingOptions::demoPath, with its intrinsics override):
/// kContactSheetSpreadFrames frames spread over the recording and every moved
/// object's grasp and release frame (perception::PerceptionDrawing: palm, each
/// part and container with outline, name and confidence, the perceived scene's
/// table frame and rectangle), the events captioned ("GRASP toy") and framed in
/// colour, an event of low confidence (motion's ObjectSegmentation::graspLowConfidence / releaseLowConfidence)
/// flagged "LOW CONFIDENCE" in red. Returns the path written.
std::vector<std::string> writeContactSheet(const std::string& dir, const ProgrammingOptions& options,
                                           const perception::PerceptionResult& seen, const core::ObjectCatalogue& kb,
                                           const motion::Segmentation& segmentation,
                                           const std::optional<taskdb::PerceivedScene>& scene);

/// The hand trajectory figure alone (x, y, z over time with detections
/// marked, and the top view with grasp/release points).
void writeHandFigure(const std::string& pngPath, const perception::PerceptionResult& seen,
                     const motion::Segmentation& segmentation);

}  // namespace srp::programming
