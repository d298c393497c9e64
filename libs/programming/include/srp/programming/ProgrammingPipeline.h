#pragma once
/// \file ProgrammingPipeline.h
/// \brief The Programming Module (thesis ch. 7.3, fig. 7.7/7.8): one
/// instruction + one RGB-D demonstration -> one task model in the database.
///
/// Stages: Language (instruction -> plan) -> grounding of the plan's objects
/// in the knowledge base -> Environment (hand and object trajectories, guided
/// by the plan: step objects move, landmarks are static) -> Motion
/// (segmentation into Reach/Grasp/Move/Release, DMPs) -> one task model
/// written in a single transaction. Every check happens before the write, so a
/// bad input or a kill at any point leaves the database as it was.
///
/// \code
///   srp::programming::ProgrammingOptions o;
///   o.instruction = "Pick up the cuboid from the blue box and place it in the gray box.";
///   o.demoPath = "demo.rawlog";  o.dbPath = "task.db";  o.name = "cuboid";
///   srp::programming::ProgramResult r = srp::programming::programTask(o);
///   // r.taskModelId, r.objects[i].graspFrame / releaseFrame, r.skills
/// \endcode

#include "srp/programming/ProgramResult.h"
#include "srp/programming/ProgrammingOptions.h"

namespace srp::programming {

/// Runs the whole pipeline and stores the task model with the scene the
/// demonstration showed. Throws (writing nothing: no database file is created
/// and no report folder is left) InvalidInputError when the instruction has no
/// steps (the message says why), names an object the knowledge base does not
/// know or the demo never shows, the hand is never seen, or (without
/// allowPartial) a step has no grasp or no release; FileError for a bad rawlog
/// or database.
ProgramResult programTask(const ProgrammingOptions& options);

}  // namespace srp::programming
