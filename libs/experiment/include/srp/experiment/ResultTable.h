#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace srp::experiment {

/**
 * One table of an experiment report, laid out like the thesis table it
 * reproduces: every row shows the thesis' number beside ours.
 *
 * Cells are already formatted text (the experiment chooses the precision);
 * the machine-readable numbers go to ExperimentResult::metrics. A cell
 * without a thesis counterpart is written "—".
 */
struct ResultTable
{
  std::string title;                           ///< e.g. "Table 8.2: hand detected (% of hand-visible frames)"
  std::vector<std::string> columns;            ///< header row
  std::vector<std::vector<std::string>> rows;  ///< each row has columns.size() cells
  std::string note;                            ///< where the thesis numbers come from, caveats

  /// GitHub-flavoured Markdown: title in bold, the table, the note in italics.
  /// Throws srp::core::InvalidInputError if a row's width differs from the header's.
  std::string toMarkdown() const;

  /// The table as aligned plain text for a terminal.
  std::string toText() const;

  /// {"title", "columns", "rows", "note"}.
  nlohmann::json toJson() const;
};

/// Formats a value with a fixed number of decimals ("—" for NaN).
std::string formatNumber(double value, int decimals);

/// Formats a fraction in [0, 1] as a percentage with the given decimals ("—" for NaN).
std::string formatPercent(double fraction, int decimals = 1);

}  // namespace srp::experiment
