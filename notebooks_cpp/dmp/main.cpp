// Notebook: learned and adapted DMPs (thesis figs. 8.6-8.8)
// ===========================================================
//
// What the figure shows
//   The thesis learns each Reach and Move segment of the demonstrated hand
//   trajectory as a discrete dynamic movement primitive (N = 20 basis
//   functions, ridge regression w = (Phi^T Phi + lambda I)^-1 Phi^T f) and
//   re-targets it to a new start and goal. Fig. 8.6 shows the Reach skill with
//   lambda = 0 (the DMP copies the demo's jitter), fig. 8.7 the same with
//   lambda = 0.1 (smoother, but it no longer follows the demo), fig. 8.8 the
//   Move skill with lambda = 0.1.
//
//   Here the input is the thesis' own data: the cuboid's Reach and Move
//   segments of its real demonstration (21 samples each, camera frame, from
//   the SRP repository, datasets/reference/dmp/inputs). Each is learned three
//   ways, one row of the figure each:
//     lambda = 0    the thesis' formulation (Dmp Reference mode = dfki-ric
//                   movement_primitives, which the thesis used), fig. 8.6;
//     lambda = 0.1  the same with the thesis' lambda, figs. 8.7 / 8.8;
//     automatic     srp's default: start/goal velocities from the demo, a
//                   correct integrator, lambda minimising the GCV error.
//   Columns are the camera-frame coordinates x, y, z over time. Grey dots:
//   the demonstration; blue: the DMP's reproduction (same start and goal);
//   orange dashed: the adaptation to a new start and goal (red crosses,
//   shifted by (+5, -3, +2) cm and (-4, +6, -1) cm as in the reference data).
//   In the lambda = 0 / 0.1 rows the small green squares are the reference
//   library's own output (its CSV), which our Reference mode reproduces.
//
// Output (in the folder given as the first argument, default out/notebooks/dmp)
//   dmp_reach.png  (copied to notebooks_cpp/dmp/figure.png), dmp_move.png,
//   dmp.txt: per skill and setting the lambda, the largest distance of the
//   reproduction from the demo, the adapted goal error, and the deviation
//   from the reference library.
//
// Run
//   cmake --build build --target notebook_dmp && build/notebooks_cpp/notebook_dmp [out_dir]
//   (CTest: ctest --test-dir build -R notebook.dmp). Takes well under a second.
//
// Checks (exit code 1 when one fails, so this page cannot rot): Reference mode
// equals the library to 1e-8 m; the automatic lambda reproduces the demo to
// within 5 mm and reaches the new goal to within 1 mm.

#include <Eigen/Core>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "../common/Notebook.h"
#include "srp/core/Error.h"
#include "srp/motion/Dmp.h"
#include "srp/plot/Figure.h"

namespace {

using srp::motion::Dmp;
using srp::motion::DmpRollout;
using srp::plot::Colour;
using srp::plot::Marker;

const std::string kReferenceDir = std::string(SRP_DATASETS_DIR) + "/reference/dmp";

// Reads a numeric CSV with one header line; returns rows x columns.
Eigen::MatrixXd readCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw srp::core::FileError(path, "cannot open (the repository's datasets/reference/dmp is needed)");
  std::string line;
  std::getline(in, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  Eigen::MatrixXd m(rows.size(), rows.empty() ? 0 : rows[0].size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < rows[r].size(); ++c) m(r, c) = rows[r][c];
  return m;
}

std::vector<double> column(const Eigen::MatrixXd& m, int c) {
  return std::vector<double>(m.col(c).data(), m.col(c).data() + m.rows());
}
std::vector<double> toVector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

// Largest pointwise distance between two trajectories sampled at the same times [m].
double maxDistance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const Eigen::Index n = std::min(a.rows(), b.rows());
  return (a.topRows(n) - b.topRows(n)).rowwise().norm().maxCoeff();
}

// One way of learning a segment: a row of the figure.
struct Setting {
  std::string name;       // how lambda is set
  std::string fileLambda; // the reference files' suffix ("0.0", "0.1"), empty: none
  Dmp::Options config;
};

// What one setting gives for one segment.
struct Outcome {
  double lambda = 0.0;
  double reproductionError_m = 0.0;   // max |reproduction - demo|
  double adaptedGoalError_m = 0.0;    // |y(T) - new goal|
  double referenceDeviation_m = -1.0; // max |ours - library| over reproduction and adaptation; -1: no reference
};

}  // namespace

int run(int argc, char** argv) {
  const std::filesystem::path out = srp::notebook::outputFolder(argc, argv, "dmp");
  std::ofstream report(out / "dmp.txt");
  srp::notebook::Checks checks;

  // The three settings of the figure's rows. The thesis' code is dfki-ric
  // movement_primitives with lambda 0 or 0.1; Dmp::Options::reference(lambda)
  // is that formulation. The default Dmp::Options chooses lambda itself.
  const std::vector<Setting> settings = {
      {"thesis", "0.0", Dmp::Options::reference(0.0)},
      {"thesis", "0.1", Dmp::Options::reference(0.1)},
      {"srp, by GCV", "", Dmp::Options{}},
  };

  for (const std::string skill : {"reach", "move"}) {
    const std::string segment = "cuboid_" + skill;
    // The thesis' figure of each (skill, lambda): Reach 0 -> 8.6, Reach 0.1 -> 8.7, Move 0.1 -> 8.8.
    const auto thesisFigure = [&](const std::string& fileLambda) -> std::string {
      if (skill == "reach" && fileLambda == "0.0") return ", fig. 8.6";
      if (skill == "reach" && fileLambda == "0.1") return ", fig. 8.7";
      if (skill == "move" && fileLambda == "0.1") return ", fig. 8.8";
      return "";
    };

    // Step 1: the demonstrated segment. 21 positions of the palm in the
    // camera frame; the thesis' code sampled them at T = linspace(0, 1, 21).
    const Eigen::MatrixXd demo = readCsv(kReferenceDir + "/inputs/" + segment + ".csv");
    const Eigen::VectorXd t_s = Eigen::VectorXd::LinSpaced(demo.rows(), 0.0, 1.0);

    // Step 2: the new start and goal: the reference data's shift of the
    // demo's start by (+5, -3, +2) cm and of its goal by (-4, +6, -1) cm.
    const Eigen::MatrixXd startGoal = readCsv(kReferenceDir + "/" + segment + "_start_goal.csv");
    const Eigen::VectorXd newStart = startGoal.row(2).transpose(), newGoal = startGoal.row(3).transpose();

    srp::plot::Figure fig(1500, 1050, 3, 3);
    fig.title = "Cuboid " + skill + " segment of the thesis' demo: DMP reproduction and adaptation (N = 20)";
    for (std::size_t row = 0; row < settings.size(); ++row) {
      const Setting& setting = settings[row];

      // Step 3: learn. imitate() fits the forcing term's weights to the demo
      // and leaves the DMP configured to reproduce it.
      Dmp dmp = Dmp::imitate(t_s, demo, setting.config);
      const DmpRollout reproduction = dmp.rollout(0.05);

      // Step 4: adapt. Only start and goal change; the duration stays 1 s.
      dmp.configure(newStart, newGoal);
      const DmpRollout adaptation = dmp.rollout(0.05);

      Outcome o;
      o.lambda = dmp.lambda();
      o.reproductionError_m = maxDistance(reproduction.y, demo);
      o.adaptedGoalError_m = (adaptation.y.bottomRows(1).transpose() - newGoal).norm();

      // Step 5 (Reference rows): the same numbers from the library itself.
      Eigen::MatrixXd libReproduction, libAdaptation;
      if (!setting.fileLambda.empty()) {
        const std::string prefix = kReferenceDir + "/" + segment + "_lambda" + setting.fileLambda;
        libReproduction = readCsv(prefix + "_reproduction.csv").rightCols(3);
        libAdaptation = readCsv(prefix + "_adapted.csv").rightCols(3);
        o.referenceDeviation_m =
            std::max(maxDistance(reproduction.y, libReproduction), maxDistance(adaptation.y, libAdaptation));
      }

      char line[256];
      std::snprintf(line, sizeof line,
                    "%-6s %-12s lambda %-9.3g reproduction max %6.2f mm from the demo, adapted goal error %6.3f mm",
                    skill.c_str(), setting.name.c_str(), o.lambda, 1e3 * o.reproductionError_m,
                    1e3 * o.adaptedGoalError_m);
      std::string text = line;
      if (o.referenceDeviation_m >= 0) {
        std::snprintf(line, sizeof line, ", %.1e m from movement_primitives", o.referenceDeviation_m);
        text += line;
      }
      std::cout << text << "\n";
      report << text << "\n";

      // Checks: the port is exact, and the default follows the demo and reaches the goal.
      constexpr double kReferenceTol_m = 1e-8, kReproductionTol_m = 5e-3, kGoalTol_m = 1e-3;
      checks.require(o.referenceDeviation_m <= kReferenceTol_m,
                     segment + " lambda " + setting.fileLambda + ": equal to the reference library to 1e-8 m");
      if (setting.fileLambda.empty()) {
        checks.require(o.reproductionError_m <= kReproductionTol_m, segment + " automatic lambda: reproduction within 5 mm");
        checks.require(o.adaptedGoalError_m <= kGoalTol_m, segment + " automatic lambda: new goal reached to 1 mm");
      }

      // Step 6: one panel per coordinate.
      const char* axisNames[] = {"x", "y", "z"};
      for (int d = 0; d < 3; ++d) {
        auto& ax = fig.axes(static_cast<int>(row), d);
        char title[160];
        std::snprintf(title, sizeof title, "%s, lambda = %.2g (%s%s): %s", skill.c_str(), o.lambda,
                      setting.name.c_str(), thesisFigure(setting.fileLambda).c_str(), axisNames[d]);
        ax.title = title;
        ax.xLabel = "t [s]";
        ax.yLabel = std::string(axisNames[d]) + " (camera) [m]";
        // The legend goes where the curves leave room: top right of y (Reach), of x (Move).
        const bool withLegend = d == (skill == "reach" ? 1 : 0);
        ax.scatter(toVector(t_s), column(demo, d), withLegend ? "demonstration" : "", Colour::gray(), Marker::Circle, 4);
        ax.line(toVector(reproduction.t_s), column(reproduction.y, d), withLegend ? "reproduction" : "", Colour::tab(0));
        ax.line(toVector(adaptation.t_s), column(adaptation.y, d), withLegend ? "adaptation" : "", Colour::tab(1), 2.0, true);
        ax.scatter({0.0, 1.0}, {newStart(d), newGoal(d)}, withLegend ? "new start / goal" : "", Colour::tab(3),
                   Marker::Cross, 6);
        if (libReproduction.size() > 0) {
          ax.scatter(toVector(t_s), column(libReproduction, d), withLegend ? "movement_primitives" : "", Colour::tab(2),
                     Marker::Square, 2);
          ax.scatter(toVector(t_s), column(libAdaptation, d), "", Colour::tab(2), Marker::Square, 2);
        }
      }
    }
    const std::filesystem::path png = out / ("dmp_" + skill + ".png");
    fig.save(png.string());
    std::cout << "wrote " << png.string() << "\n";
  }

  // The test fails when a figure is missing.
  for (const char* name : {"dmp_reach.png", "dmp_move.png"}) checks.pngWritten(out / name);
  return checks.exitCode();
}

int main(int argc, char** argv) { return srp::notebook::run("dmp", argc, argv, run); }
