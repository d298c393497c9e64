#include "srp/experiment/ResultTable.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "srp/core/Error.h"

namespace srp::experiment {
namespace {

void checkShape(const ResultTable& table)
{
  for (size_t r = 0; r < table.rows.size(); ++r)
    if (table.rows[r].size() != table.columns.size())
      throw core::InvalidInputError("table '" + table.title + "': row " + std::to_string(r) + " has " +
                                    std::to_string(table.rows[r].size()) + " cells, the header " +
                                    std::to_string(table.columns.size()) + "; give every row one cell per column");
}

// Display width in characters, counting a UTF-8 sequence (°, —, ±) as one.
size_t displayWidth(const std::string& s)
{
  return static_cast<size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

std::string escapeCell(const std::string& s)
{
  std::string out;
  for (char c : s) out += (c == '|') ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

std::string ResultTable::toMarkdown() const
{
  checkShape(*this);
  std::ostringstream out;
  if (!title.empty()) out << "**" << title << "**\n\n";
  out << '|';
  for (const auto& c : columns) out << ' ' << escapeCell(c) << " |";
  out << "\n|";
  for (size_t i = 0; i < columns.size(); ++i) out << (i == 0 ? "---|" : "---:|");
  out << '\n';
  for (const auto& row : rows) {
    out << '|';
    for (const auto& cell : row) out << ' ' << escapeCell(cell) << " |";
    out << '\n';
  }
  if (!note.empty()) out << "\n*" << note << "*\n";
  return out.str();
}

std::string ResultTable::toText() const
{
  checkShape(*this);
  std::vector<size_t> width(columns.size(), 0);
  for (size_t i = 0; i < columns.size(); ++i) width[i] = displayWidth(columns[i]);
  for (const auto& row : rows)
    for (size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], displayWidth(row[i]));
  auto line = [&](const std::vector<std::string>& cells) {
    std::string s;
    for (size_t i = 0; i < cells.size(); ++i) {
      const std::string pad(width[i] - displayWidth(cells[i]), ' ');
      s += (i == 0) ? cells[i] + pad : "  " + pad + cells[i];
    }
    return s + '\n';
  };
  std::string out = title.empty() ? std::string() : title + '\n';
  out += line(columns);
  size_t total = 0;
  for (size_t i = 0; i < width.size(); ++i) total += width[i] + (i == 0 ? 0 : 2);
  out += std::string(total, '-') + '\n';
  for (const auto& row : rows) out += line(row);
  if (!note.empty()) out += note + '\n';
  return out;
}

nlohmann::json ResultTable::toJson() const
{
  checkShape(*this);
  return {{"title", title}, {"columns", columns}, {"rows", rows}, {"note", note}};
}

std::string formatNumber(double value, int decimals)
{
  if (std::isnan(value)) return "—";
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << value;
  return s.str();
}

std::string formatPercent(double fraction, int decimals)
{
  if (std::isnan(fraction)) return "—";
  return formatNumber(100.0 * fraction, decimals) + " %";
}

}  // namespace srp::experiment
