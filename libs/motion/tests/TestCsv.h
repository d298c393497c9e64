#pragma once
// Test helper: reads a numeric CSV with one header line (the reference DMP files).
#include <Eigen/Core>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace srp::motion::test {

inline Eigen::MatrixXd readCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  Eigen::MatrixXd M(rows.size(), rows.empty() ? 0 : rows[0].size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < rows[r].size(); ++c) M(r, c) = rows[r][c];
  return M;
}

inline std::string referenceDir() { return std::string(SRP_DATASETS_DIR) + "/reference/dmp/"; }

inline const std::vector<std::string>& referenceDemos() {
  static const std::vector<std::string> demos = {
      "cuboid_reach", "cuboid_move", "star_reach", "star_move",
      "parallelogram_reach", "parallelogram_move", "octagon_reach", "octagon_move"};
  return demos;
}

}  // namespace srp::motion::test
