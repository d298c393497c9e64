#pragma once

#include <optional>
#include <string>
#include <vector>

#include "srp/experiment/ExperimentResult.h"

namespace srp::experiment {

/// One entry of `srp experiment`: its name, a one-line description, the function.
struct ExperimentInfo
{
  std::string name;
  std::string description;
  ExperimentFunction run;
};

/// Every experiment of thesis chapter 8 in report order (language, hand,
/// objects, depth, segmentation, dmp, execution); `all` is not one of them.
const std::vector<ExperimentInfo>& experiments();

/// The experiment called `name`, or nullopt.
std::optional<ExperimentInfo> findExperiment(const std::string& name);

// One function per experiment, each in its own src/<Name>Experiment.cpp.
ExperimentResult runLanguageExperiment(const ExperimentOptions& options);      ///< tables 5.7/D.1-D.3, 8.1
ExperimentResult runHandExperiment(const ExperimentOptions& options);          ///< table 8.2
ExperimentResult runObjectsExperiment(const ExperimentOptions& options);       ///< tables 8.3/8.4
ExperimentResult runDepthExperiment(const ExperimentOptions& options);         ///< section 8.3.3
ExperimentResult runSegmentationExperiment(const ExperimentOptions& options);  ///< section 8.3.4, fig. 8.5
ExperimentResult runDmpExperiment(const ExperimentOptions& options);           ///< section 8.4, figs. 8.6-8.8
ExperimentResult runExecutionExperiment(const ExperimentOptions& options);     ///< section 8.5.2

}  // namespace srp::experiment
