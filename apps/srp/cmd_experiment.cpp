// `srp experiment <name>`: the thesis' chapter 8 evaluation on our system, the
// thesis' numbers beside ours (libs/experiment).
#include <iostream>

#include "CommandRegistry.h"
#include "CommonOptions.h"
#include "srp/core/Error.h"
#include "srp/core/ExitCode.h"
#include "srp/core/Json.h"
#include "srp/core/OutputFile.h"
#include "srp/experiment/ExperimentReport.h"
#include "srp/experiment/ExperimentSupport.h"
#include "srp/experiment/Experiments.h"

namespace {

struct ExperimentArgs {
  std::string name;
  std::string outDir = "out/experiment";
  int demos = 5;
  unsigned seed = 1;
  bool quick = false, json = false, overwrite = false;
};

void run(const ExperimentArgs& a) {
  namespace ex = srp::experiment;
  if (a.name != "all" && !ex::findExperiment(a.name))
    throw srp::core::InvalidInputError("unknown experiment '" + a.name + "'; valid names: " + ex::experimentNamesList());
  ex::ExperimentOptions options;
  options.outDir = std::filesystem::absolute(a.outDir);
  options.demoCount = a.demos;
  options.firstSeed = a.seed;
  options.quick = a.quick;
  if (srp::app::progressWanted(a.json))  // a terminal, no -q, no --json
    options.progress = [](const std::string& what, double fraction) {
      std::cerr << "[" << static_cast<int>(100.0 * fraction) << " %] " << what << "\n";
    };
  std::vector<std::string> names;
  if (a.name == "all")
    for (const auto& e : ex::experiments()) names.push_back(e.name);
  else
    names.push_back(a.name);
  // The reports are the outputs (the demo cache in <out>/demos/ is re-used on purpose).
  std::vector<srp::core::PathRole> reports;
  for (const auto& name : names) reports.push_back({"--out", options.outDir / name / "report.md"});
  if (a.name == "all") reports.push_back({"--out", options.outDir / "report.md"});
  srp::core::checkOutputPaths(reports, {}, a.overwrite);

  const ex::WallClock clock;
  std::vector<ex::ExperimentOutcome> outcomes;
  for (const auto& name : names) {
    if (!srp::app::quietFlag()) std::cerr << "srp experiment: " << name << " ...\n";
    outcomes.push_back(ex::runExperiment(name, options));
    const auto& o = outcomes.back();
    if (!o.succeeded) {
      std::cerr << "srp experiment: " << name << " failed: " << o.error << "\n";
      continue;
    }
    if (!a.json) {
      std::cout << "== " << name << " (" << ex::formatNumber(o.wallTime_s, 1) << " s) ==\n" << o.result.summary << "\n\n";
      for (const auto& t : o.result.tables) std::cout << t.toText() << "\n";
      for (const auto& f : o.result.figures) std::cout << "figure: " << f.string() << "\n";
      std::cout << "written: " << (options.outDir / name / "report.md").string() << "\n\n";
    }
  }
  const double total = clock.seconds();
  int failed = 0;
  for (const auto& o : outcomes) failed += !o.succeeded;
  if (a.name == "all") {
    srp::core::writeJsonFile((options.outDir / "result.json").string(), ex::combinedJson(outcomes, total));
    const auto md = options.outDir / "report.md";
    srp::core::writeFileAtomically(md, ex::combinedMarkdown(outcomes, options.outDir, total));
    if (!a.json)
      std::cout << "all: " << outcomes.size() - failed << "/" << outcomes.size() << " experiments done in "
                << ex::formatNumber(total, 1) << " s; report " << md.string() << "\n";
  }
  if (a.json) {
    if (a.name == "all")
      std::cout << ex::combinedJson(outcomes, total).dump(2) << "\n";
    else if (outcomes.front().succeeded)
      std::cout << outcomes.front().result.toJson().dump(2) << "\n";
  }
  // A single experiment that failed is an error; in `all` the others still ran.
  if (a.name != "all" && failed) throw srp::core::Error(outcomes.front().error);
  if (failed) srp::app::commandExitCode() = srp::core::toInt(srp::core::ExitCode::Partial);
}

void setupExperiment(CLI::App& cmd) {
  auto args = std::make_shared<ExperimentArgs>();
  cmd.add_option("name", args->name,
                 "experiment: language, hand, objects, depth, segmentation, dmp, execution, or all")
      ->required();
  cmd.add_option("-o,--out", args->outDir, "output folder; each experiment writes <out>/<name>/, 'all' also "
                                          "<out>/report.md and <out>/result.json; demos are cached in <out>/demos/")
      ->capture_default_str();
  cmd.add_option("--demos", args->demos, "number of seeded synthetic demos (the thesis had five videos)")
      ->capture_default_str();
  cmd.add_option("--seed", args->seed, "seed of the first demo (then seed+1, ...)")->capture_default_str();
  cmd.add_flag("--quick", args->quick, "smallest sizes that still exercise every part (one short 320x240 demo)");
  cmd.add_flag("--json", args->json, "print the result JSON instead of the tables");
  srp::app::addOverwriteFlag(cmd, args->overwrite);
  cmd.callback([args]() { run(*args); });
}

const srp::app::CommandRegistrar kReg{"experiment",
                                      "Run the thesis' chapter 8 experiments with the thesis' numbers beside ours",
                                      90, setupExperiment};

}  // namespace
