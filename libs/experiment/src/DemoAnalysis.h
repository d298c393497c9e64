#pragma once
// Private to the experiments: a shared demo programmed as `srp program` does,
// with its ground truth and the motion module's inputs read back from the task
// database.

#include <string>

#include "srp/experiment/DemoCache.h"
#include "srp/experiment/ExperimentResult.h"
#include "srp/programming/MotionRows.h"
#include "srp/synth/DemoGroundTruth.h"
#include "srp/taskdb/TaskModel.h"

namespace srp::experiment {

struct AnalysedDemo
{
  int index = 0;  ///< 0-based demo number of the run
  ProgrammedDemo programmed;
  synth::DemoGroundTruth groundTruth;
  taskdb::TaskModel model;      ///< as stored by programTask
  programming::MotionInputs inputs;  ///< hand and object tracks, plan order (frame = TimeId)
};

/// Standard demo `index` of the run (standardDemoRequest), rendered and
/// programmed once per cache; progress as "<experiment>: demo i/n <stage>".
AnalysedDemo analyseDemo(const ExperimentOptions& options, int index, const std::string& experiment);

/// Class name of a ground-truth object id ("" when unknown).
std::string classOf(const synth::DemoGroundTruth& groundTruth, const std::string& objectId);

/// Number of demos of a run: options.demoCount (at least 1), 1 when quick.
int demoCountOf(const ExperimentOptions& options);

}  // namespace srp::experiment
