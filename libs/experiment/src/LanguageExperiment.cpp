#include "srp/experiment/Experiments.h"

#include "srp/core/Error.h"

namespace srp::experiment {

// Placeholder while the experiment is written on its branch; replaced before it lands.
ExperimentResult runLanguageExperiment(const ExperimentOptions&)
{
  throw core::Error("experiment 'Language' is not written yet");
}

}  // namespace srp::experiment
