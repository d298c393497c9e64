#include "srp/experiment/Experiments.h"

namespace srp::experiment {

const std::vector<ExperimentInfo>& experiments()
{
  static const std::vector<ExperimentInfo> list{
      {"language", "P/R/F1 per entity and relation type on val.json and per source corpus, beside SpERT (tables 5.7, D.1-D.3, 8.1)",
       runLanguageExperiment},
      {"hand", "hand detected in % of hand-visible frames per demo and detector, 3D error (table 8.2)", runHandExperiment},
      {"objects", "per-class precision, recall, mAP50, mAP50-95, with and without language-guided refinement (tables 8.3/8.4)",
       runObjectsExperiment},
      {"depth", "valid depth on hand and objects under the sensor model, error of the filled-in depth (section 8.3.3)",
       runDepthExperiment},
      {"segmentation", "grasp/release frame errors per object against ground truth (section 8.3.4, fig. 8.5)",
       runSegmentationExperiment},
      {"dmp", "DMP reproduction and adaptation errors for lambda = 0, 0.1 and automatic (section 8.4, figs. 8.6-8.8)",
       runDmpExperiment},
      {"execution", "execution success per Appendix A instruction and per adaptation over seeded scenes (section 8.5.2)",
       runExecutionExperiment},
  };
  return list;
}

std::optional<ExperimentInfo> findExperiment(const std::string& name)
{
  for (const auto& e : experiments())
    if (e.name == name) return e;
  return std::nullopt;
}

}  // namespace srp::experiment
