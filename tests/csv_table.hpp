#pragma once
// The CSV files a run and `runout analyse` write, read as text tables:
// lines starting with '#' skipped, the first other line the header, no
// quoted commas (none of the project's tables has one).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace runout::csv_table {

struct Table {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  // The index of column `name`; fails the test and gives -1 without it.
  int column(const std::string& name) const {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return static_cast<int>(k);
    ADD_FAILURE() << "no column " << name;
    return -1;
  }
  // Row `row`'s cell of column `name`, "" without it.
  std::string cell(std::size_t row, const std::string& name) const {
    const int k = column(name);
    return k >= 0 && row < rows.size() && k < static_cast<int>(rows[row].size()) ? rows[row][k]
                                                                                 : "";
  }
  double number(std::size_t row, const std::string& name) const {
    return std::strtod(cell(row, name).c_str(), nullptr);
  }
};

inline std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

inline Table read_table(const std::filesystem::path& path) {
  Table table;
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot read " << path;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (table.header.empty())
      table.header = split(line);
    else
      table.rows.push_back(split(line));
  }
  return table;
}

}  // namespace runout::csv_table
