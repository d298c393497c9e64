#include "DemoAnalysis.h"

#include <algorithm>

#include "srp/core/Error.h"
#include "srp/experiment/ExperimentSupport.h"
#include "srp/taskdb/TaskModelStore.h"

namespace srp::experiment {

int demoCountOf(const ExperimentOptions& options)
{
  if (options.demoCount < 1)
    throw core::InvalidInputError("--demos must be at least 1 (got " + std::to_string(options.demoCount) + ")");
  return options.quick ? 1 : options.demoCount;
}

AnalysedDemo analyseDemo(const ExperimentOptions& options, int index, const std::string& experiment)
{
  AnalysedDemo out;
  out.index = index;
  const int count = demoCountOf(options);
  const DemoRequest request = standardDemoRequest(options, index);
  const std::string label = experiment + ": demo " + std::to_string(index + 1) + "/" + std::to_string(count) +
                            " (seed " + std::to_string(request.seed) + ") ";
  const double base = static_cast<double>(index) / count;
  out.programmed = demoCacheFor(options).programmed(request, [&](const std::string& stage, std::size_t done, std::size_t total) {
    if (done % 50 != 0) return;  // a line now and then, not one per frame
    const double within = total > 0 ? static_cast<double>(done) / total : 0.0;
    reportProgress(options, label + stage + " " + std::to_string(done) + (total > 0 ? "/" + std::to_string(total) : ""),
                   base + within / count * 0.9);
  });
  out.groundTruth = synth::DemoGroundTruth::load(out.programmed.demo.groundTruthPath.string());
  auto db = taskdb::TaskDatabase::open(out.programmed.databasePath.string(), taskdb::TaskDatabase::Mode::ReadOnly);
  out.model = taskdb::TaskModelStore(db).read(out.programmed.taskModelId);
  out.inputs = programming::motionInputsFromTaskModel(out.model);
  return out;
}

std::string classOf(const synth::DemoGroundTruth& groundTruth, const std::string& objectId)
{
  const auto it = std::find_if(groundTruth.objects.begin(), groundTruth.objects.end(),
                               [&](const auto& o) { return o.id == objectId; });
  return it == groundTruth.objects.end() ? std::string() : it->className;
}

}  // namespace srp::experiment
