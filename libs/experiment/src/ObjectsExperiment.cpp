#include "srp/experiment/Experiments.h"

#include "srp/core/Error.h"

namespace srp::experiment {

// Placeholder while the experiment is written on its branch; replaced before it lands.
ExperimentResult runObjectsExperiment(const ExperimentOptions&)
{
  throw core::Error("experiment 'Objects' is not written yet");
}

}  // namespace srp::experiment
