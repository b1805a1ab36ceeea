// What the studies write into their report folders (experiment/src/report_files.h): free text as
// one CSV field, numbers for tables.
#include "report_files.h"

#include <gtest/gtest.h>

#include <cmath>

namespace teleop::experiment {
namespace {

TEST(CsvQuoted, QuotesTheTextAndDoublesItsQuotes) {
  EXPECT_EQ(csv_quoted(""), "\"\"");
  EXPECT_EQ(csv_quoted("no geom, named x"), "\"no geom, named x\"");
  EXPECT_EQ(csv_quoted("geom \"panel\" missing"), "\"geom \"\"panel\"\" missing\"");
}

TEST(FormatNumber, PrintsWithTheSpecAndNaNAsADash) {
  EXPECT_EQ(format_number("%.3g", 0.0123456), "0.0123");
  EXPECT_EQ(format_number("%.1f", std::nan("")), "–");
}

}  // namespace
}  // namespace teleop::experiment
