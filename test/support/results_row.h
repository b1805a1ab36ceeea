#pragma once
// The first row of `teleop experiment --csv`'s results, by column name: what the process tests of
// the papers' tables assert on.

#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "process_helpers.h"

namespace teleop::test {

using ResultsRow = std::map<std::string, std::string>;

inline ResultsRow read_results_row(const std::string& csv_path) {
  std::istringstream lines(read_file(csv_path));
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  ResultsRow values;
  std::istringstream h(header), v(row);
  for (std::string name, value; std::getline(h, name, ',');) {
    std::getline(v, value, ',');
    values[name] = value;
  }
  return values;
}

/// The column as a number; NaN where it is missing or empty.
inline double number(const ResultsRow& row, const std::string& name) {
  const auto it = row.find(name);
  if (it == row.end() || it->second.empty()) return std::nan("");
  return std::stod(it->second);
}

}  // namespace teleop::test
