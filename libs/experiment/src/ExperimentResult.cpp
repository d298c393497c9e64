#include "srp/experiment/ExperimentResult.h"

#include <sstream>

namespace srp::experiment {

std::string ExperimentResult::toMarkdown(const std::filesystem::path& relativeTo) const
{
  std::ostringstream out;
  out << "## " << name << "\n\n";
  if (!summary.empty()) out << summary << "\n\n";
  for (const auto& table : tables) out << table.toMarkdown() << '\n';
  for (const auto& figure : figures) {
    const auto shown = relativeTo.empty() ? figure : std::filesystem::proximate(figure, relativeTo);
    out << "![" << figure.stem().string() << "](" << shown.generic_string() << ")\n\n";
  }
  std::ostringstream took;
  took.precision(1);
  took << std::fixed << wallTime_s;
  out << "*Measured in this run, " << took.str() << " s.*\n";
  return out.str();
}

nlohmann::json ExperimentResult::toJson() const
{
  nlohmann::json tablesJson = nlohmann::json::array();
  for (const auto& table : tables) tablesJson.push_back(table.toJson());
  nlohmann::json figuresJson = nlohmann::json::array();
  for (const auto& figure : figures) figuresJson.push_back(figure.generic_string());
  return {{"name", name},       {"summary", summary}, {"tables", tablesJson},
          {"figures", figuresJson}, {"metrics", metrics.is_null() ? nlohmann::json::object() : metrics},
          {"wall_time_s", wallTime_s}};
}

}  // namespace srp::experiment
