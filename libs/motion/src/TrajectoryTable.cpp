#include "srp/motion/TrajectoryTable.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "srp/core/Error.h"

namespace srp::motion {
namespace {

using core::InvalidInputError;

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    while (!cell.empty() && (cell.back() == '\r' || cell.back() == ' ')) cell.pop_back();
    while (!cell.empty() && cell.front() == ' ') cell.erase(cell.begin());
    cells.push_back(cell);
  }
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() > suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

TrajectoryTable TrajectoryTable::readCsv(const std::string& path, double frameRate_hz) {
  core::require(frameRate_hz > 0 && std::isfinite(frameRate_hz), "frame rate must be positive");
  std::ifstream in(path);
  if (!in) throw core::FileError(path, "cannot open the trajectory table");
  std::string line;
  if (!std::getline(in, line)) throw core::FileError(path, "empty file; expected a header line");
  const std::vector<std::string> header = splitCsv(line);
  const std::string where = path + ": ";
  if (header.size() < 4 || header[0] != "frame" || header[1] != "hand_x" || header[2] != "hand_y" || header[3] != "hand_z")
    throw InvalidInputError(where + "header must start with frame,hand_x,hand_y,hand_z");
  if ((header.size() - 4) % 4 != 0)
    throw InvalidInputError(where + "after the hand, each object needs 4 columns <name>_x,<name>_y,<name>_z,<name>_rz");
  TrajectoryTable table;
  table.hand = core::PositionTrajectory("camera");
  for (std::size_t c = 4; c < header.size(); c += 4) {
    if (!endsWith(header[c], "_x")) throw InvalidInputError(where + "column '" + header[c] + "' should be <name>_x");
    const std::string name = header[c].substr(0, header[c].size() - 2);
    if (header[c + 1] != name + "_y" || header[c + 2] != name + "_z" || header[c + 3] != name + "_rz")
      throw InvalidInputError(where + "columns after '" + header[c] + "' must be " + name + "_y," + name + "_z," +
                              name + "_rz");
    for (const auto& o : table.objects)
      if (o.name == name) throw InvalidInputError(where + "object '" + name + "' appears twice in the header");
    ObjectTrack t;
    t.name = name;
    t.positions = core::PositionTrajectory("camera");
    table.objects.push_back(std::move(t));
  }
  int lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty() || line == "\r") continue;
    const auto cells = splitCsv(line);
    if (cells.size() != header.size())
      throw InvalidInputError(where + "line " + std::to_string(lineNo) + " has " + std::to_string(cells.size()) +
                              " columns, the header " + std::to_string(header.size()));
    std::vector<double> v(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) {
      std::size_t used = 0;
      try {
        v[c] = std::stod(cells[c], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != cells[c].size())
        throw InvalidInputError(where + "line " + std::to_string(lineNo) + ", column '" + header[c] +
                                "': '" + cells[c] + "' is not a number");
      if (!std::isfinite(v[c]))
        throw InvalidInputError(where + "line " + std::to_string(lineNo) + ", column '" + header[c] +
                                "' is NaN/infinite; write 0,0,0 for a sample that was not detected");
    }
    const int frame = static_cast<int>(std::lround(v[0]));
    if (!table.hand.empty() && frame <= table.hand.samples().back().frame)
      throw InvalidInputError(where + "line " + std::to_string(lineNo) + ": frame " + std::to_string(frame) +
                              " does not increase");
    const double t = frame / frameRate_hz;
    auto sample = [&](std::size_t c) {
      core::PositionSample s;
      s.frame = frame;
      s.t_s = t;
      s.p_m = Eigen::Vector3d(v[c], v[c + 1], v[c + 2]);
      s.valid = !(s.p_m.array() == 0.0).all();
      return s;
    };
    table.hand.append(sample(1));
    for (std::size_t k = 0; k < table.objects.size(); ++k) {
      table.objects[k].positions.append(sample(4 + 4 * k));
      table.objects[k].yaw_rad.push_back(v[7 + 4 * k]);
    }
  }
  if (table.hand.size() < 2)
    throw InvalidInputError(where + "has " + std::to_string(table.hand.size()) + " data rows; a demo needs at least 2");
  return table;
}

void TrajectoryTable::writeCsv(const std::string& path) const {
  std::ofstream out(path);
  if (!out) throw core::FileError(path, "cannot write the trajectory table");
  out << "frame,hand_x,hand_y,hand_z";
  for (const auto& o : objects) out << "," << o.name << "_x," << o.name << "_y," << o.name << "_z," << o.name << "_rz";
  out << "\n";
  char buf[64];
  auto num = [&](double x) {
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return std::string(buf);
  };
  for (std::size_t i = 0; i < hand.size(); ++i) {
    const auto& h = hand[i];
    const Eigen::Vector3d ph = h.valid ? h.p_m : Eigen::Vector3d::Zero();
    out << h.frame << "," << num(ph.x()) << "," << num(ph.y()) << "," << num(ph.z());
    for (const auto& o : objects) {
      const auto& s = o.positions[i];
      const Eigen::Vector3d p = s.valid ? s.p_m : Eigen::Vector3d::Zero();
      out << "," << num(p.x()) << "," << num(p.y()) << "," << num(p.z()) << ","
          << num(o.yaw_rad.empty() ? 0.0 : o.yaw_rad[i]);
    }
    out << "\n";
  }
  if (!out) throw core::FileError(path, "write failed");
}

}  // namespace srp::motion
