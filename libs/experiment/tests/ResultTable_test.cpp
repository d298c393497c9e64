#include "srp/experiment/ResultTable.h"

#include <gtest/gtest.h>

#include <cmath>

#include "srp/core/Error.h"
#include "srp/experiment/ExperimentResult.h"

using namespace srp::experiment;

namespace {
ResultTable sampleTable()
{
  ResultTable t;
  t.title = "Table 8.2: hand detected";
  t.columns = {"demo", "thesis", "ours"};
  t.rows = {{"1", "91.7 %", "100.0 %"}, {"2", "100.0 %", "98.5 %"}};
  t.note = "thesis: best model";
  return t;
}
}  // namespace

TEST(ResultTable, MarkdownHasHeaderSeparatorAndRows)
{
  const std::string md = sampleTable().toMarkdown();
  EXPECT_NE(md.find("**Table 8.2: hand detected**"), std::string::npos);
  EXPECT_NE(md.find("| demo | thesis | ours |\n|---|---:|---:|\n"), std::string::npos);
  EXPECT_NE(md.find("| 2 | 100.0 % | 98.5 % |"), std::string::npos);
  EXPECT_NE(md.find("*thesis: best model*"), std::string::npos);
}

TEST(ResultTable, TextColumnsAlignWithUtf8Cells)
{
  ResultTable t;
  t.columns = {"type", "error"};
  t.rows = {{"yaw", "3.0°"}, {"position", "12.5 mm"}};
  const std::string text = t.toText();
  // "3.0°" is 4 display characters: right-aligned under "error" at width 7.
  EXPECT_NE(text.find("yaw          3.0°\n"), std::string::npos) << text;
  EXPECT_NE(text.find("position  12.5 mm\n"), std::string::npos) << text;
}

TEST(ResultTable, RaggedRowIsAnError)
{
  ResultTable t = sampleTable();
  t.rows.push_back({"3", "x"});
  EXPECT_THROW(t.toMarkdown(), srp::core::InvalidInputError);
  EXPECT_THROW(t.toJson(), srp::core::InvalidInputError);
}

TEST(ResultTable, NumberFormatting)
{
  EXPECT_EQ(formatNumber(3.14159, 2), "3.14");
  EXPECT_EQ(formatPercent(0.9166, 1), "91.7 %");
  EXPECT_EQ(formatNumber(std::nan(""), 1), "—");
}

TEST(ExperimentResult, JsonAndMarkdownCarryTablesAndFigures)
{
  ExperimentResult r;
  r.name = "hand";
  r.summary = "five demos";
  r.tables.push_back(sampleTable());
  r.figures.push_back("/tmp/out/hand/errors.png");
  r.metrics["median_error_m"] = 0.0012;
  r.wallTime_s = 12.34;
  const auto j = r.toJson();
  EXPECT_EQ(j.at("tables").size(), 1u);
  EXPECT_DOUBLE_EQ(j.at("metrics").at("median_error_m").get<double>(), 0.0012);
  const std::string md = r.toMarkdown("/tmp/out");
  EXPECT_NE(md.find("## hand"), std::string::npos);
  EXPECT_NE(md.find("![errors](hand/errors.png)"), std::string::npos) << md;
  EXPECT_NE(md.find("12.3 s"), std::string::npos);
}
