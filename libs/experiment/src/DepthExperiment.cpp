#include "srp/experiment/Experiments.h"

#include "srp/core/Error.h"

namespace srp::experiment {

// Placeholder while the experiment is written on its branch; replaced before it lands.
ExperimentResult runDepthExperiment(const ExperimentOptions&)
{
  throw core::Error("experiment 'Depth' is not written yet");
}

}  // namespace srp::experiment
