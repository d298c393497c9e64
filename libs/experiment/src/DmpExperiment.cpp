// `srp experiment dmp`: Reach and Move DMPs learned from the hand trajectories of
// programmed synthetic demos, reproduced and adapted to a new start and goal, for
// lambda = 0, 0.1 (the thesis' formulation, dfki-ric movement_primitives) and
// our default formulation with lambda = 0, 0.1 and automatic (GCV)
// (thesis section 8.4, figs. 8.6-8.8).
#include <algorithm>
#include <cmath>

#include "DemoAnalysis.h"
#include "srp/core/Error.h"
#include "srp/experiment/Experiments.h"
#include "srp/experiment/ExperimentSupport.h"
#include "srp/motion/Dmp.h"
#include "srp/motion/LearnSkills.h"
#include "srp/motion/Segmenter.h"
#include "srp/motion/SkillLearner.h"
#include "srp/motion/SkillPlots.h"
#include "srp/plot/Figure.h"

namespace srp::experiment {
namespace {

struct Variant
{
  std::string name;
  motion::Dmp::Options config;
};

std::vector<Variant> variants()
{
  motion::Dmp::Options zero, tenth, gcv;
  zero.lambda = 0.0;
  tenth.lambda = 0.1;
  return {{"thesis formulation, λ = 0", motion::Dmp::Options::reference(0.0)},
          {"thesis formulation, λ = 0.1", motion::Dmp::Options::reference(0.1)},
          {"ours, λ = 0", zero},
          {"ours, λ = 0.1", tenth},
          {"ours, λ automatic (GCV)", gcv}};
}

/// One demo segment: times from 0 [s] and positions [m] (camera frame).
struct Segment
{
  std::string label;  ///< "cuboid reach (seed 1)"
  std::string skill;  ///< "reach" / "move"
  Eigen::VectorXd t_s;
  Eigen::MatrixXd Y;
};

/// Rollout positions at times t (linear interpolation; held at the ends).
Eigen::MatrixXd sampleAt(const motion::DmpRollout& r, const Eigen::VectorXd& t)
{
  Eigen::MatrixXd out(t.size(), r.y.cols());
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    const double* begin = r.t_s.data();
    const double* end = begin + r.t_s.size();
    const double* it = std::lower_bound(begin, end, t(i));
    if (it == begin) {
      out.row(i) = r.y.row(0);
    } else if (it == end) {
      out.row(i) = r.y.row(r.y.rows() - 1);
    } else {
      const Eigen::Index k = it - begin;
      const double a = (t(i) - r.t_s(k - 1)) / std::max(r.t_s(k) - r.t_s(k - 1), 1e-12);
      out.row(i) = (1.0 - a) * r.y.row(k - 1) + a * r.y.row(k);
    }
  }
  return out;
}

struct Outcome
{
  double reproductionMax_m = NAN, reproductionRms_m = NAN;
  double adaptedGoal_m = NAN;   ///< |y(T) - g'| after re-targeting
  double adaptedShape_m = NAN;  ///< max distance to the demo shifted by the blend of the start and goal shifts
  double lambda = NAN;
  motion::DmpRollout reproduction, adaptation;
};

Outcome evaluate(const Segment& s, const motion::Dmp::Options& config, const motion::AdaptationShift& shift)
{
  Outcome o;
  motion::Dmp dmp = motion::Dmp::imitate(s.t_s, s.Y, config);
  o.lambda = dmp.lambda();
  const double dt = s.t_s(1) - s.t_s(0);
  o.reproduction = dmp.rollout(dt);
  const Eigen::MatrixXd rep = sampleAt(o.reproduction, s.t_s);
  const Eigen::VectorXd d = (rep - s.Y).rowwise().norm();
  o.reproductionMax_m = d.maxCoeff();
  o.reproductionRms_m = std::sqrt(d.squaredNorm() / static_cast<double>(d.size()));

  const Eigen::Vector3d start = s.Y.row(0).transpose() + shift.start_m;
  const Eigen::Vector3d goal = s.Y.row(s.Y.rows() - 1).transpose() + shift.goal_m;
  const double T = s.t_s(s.t_s.size() - 1);
  dmp.configure(start, goal, T);
  o.adaptation = dmp.rollout(dt);
  o.adaptedGoal_m = (o.adaptation.y.row(o.adaptation.y.rows() - 1).transpose() - goal).norm();
  const Eigen::MatrixXd ad = sampleAt(o.adaptation, s.t_s);
  double shape = 0.0;
  for (Eigen::Index i = 0; i < s.t_s.size(); ++i) {
    const double a = s.t_s(i) / T;
    const Eigen::Vector3d expected = s.Y.row(i).transpose() + (1.0 - a) * shift.start_m + a * shift.goal_m;
    shape = std::max(shape, (ad.row(i).transpose() - expected).norm());
  }
  o.adaptedShape_m = shape;
  return o;
}

double worst(const std::vector<double>& v) { return v.empty() ? NAN : *std::max_element(v.begin(), v.end()); }

std::vector<double> column(const Eigen::MatrixXd& m, int c)
{
  std::vector<double> out(static_cast<size_t>(m.rows()));
  for (Eigen::Index i = 0; i < m.rows(); ++i) out[static_cast<size_t>(i)] = m(i, c);
  return out;
}

std::vector<double> toStd(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

// Figs. 8.6-8.8: per axis, the demo, the reproduction and the adaptation of the
// thesis formulation, and ours (GCV) dashed.
void writeDmpFigure(const std::string& path, const std::string& title, const Segment& s, const Outcome& thesis,
                    const Outcome& ours, const motion::AdaptationShift& shift)
{
  plot::Figure fig(1000, 900, 3, 1);
  fig.title = title;
  const char* axisName[3] = {"x [m]", "y [m]", "z [m]"};
  const double T = s.t_s(s.t_s.size() - 1);
  for (int c = 0; c < 3; ++c) {
    auto& ax = fig.axes(c, 0);
    ax.xLabel = "t [s]";
    ax.yLabel = axisName[c];
    ax.line(toStd(s.t_s), column(s.Y, c), "demonstration", plot::Colour{0, 0, 0}, 2.0);
    ax.line(toStd(thesis.reproduction.t_s), column(thesis.reproduction.y, c), "reproduction (thesis)", plot::Colour::tab(0));
    ax.line(toStd(thesis.adaptation.t_s), column(thesis.adaptation.y, c), "adaptation (thesis)", plot::Colour::tab(1));
    ax.line(toStd(ours.reproduction.t_s), column(ours.reproduction.y, c), "reproduction (ours, GCV)", plot::Colour::tab(2),
            2.0, true);
    ax.line(toStd(ours.adaptation.t_s), column(ours.adaptation.y, c), "adaptation (ours, GCV)", plot::Colour::tab(3), 2.0,
            true);
    ax.scatter({0.0}, {s.Y(0, c) + shift.start_m(c)}, "new start", plot::Colour::tab(4), plot::Marker::Square, 7.0);
    ax.scatter({T}, {s.Y(s.Y.rows() - 1, c) + shift.goal_m(c)}, "new goal", plot::Colour::tab(5), plot::Marker::Triangle,
               7.0);
    ax.legend = c == 0;
  }
  fig.save(path);
}

std::string mm(double m) { return formatNumber(1e3 * m, 2); }

/// Reach and Move segments of every moved object in `count` demos: the smoothed hand between
/// the segmentation's events, as SkillLearner learns them.
std::vector<Segment> demoSegments(const ExperimentOptions& options, int count, const std::string& name)
{
  std::vector<Segment> segments;
  for (int d = 0; d < count; ++d) {
    const AnalysedDemo demo = analyseDemo(options, d, name);
    const auto& in = demo.inputs;
    const motion::LearnedSkills learned = motion::learnSkills(in);
    const auto& seg = learned.segmentation;
    const auto& skills = learned.skills;
    const auto& hand = seg.hand;
    for (const auto& s : skills) {
      const auto make = [&](const std::string& skill, int from, int to) {
        Segment out;
        out.skill = skill;
        out.label = s.objectName + " " + skill + " (seed " + std::to_string(demo.groundTruth.seed) + ")";
        const int n = to - from + 1;
        if (n < 3) return;
        out.t_s.resize(n);
        out.Y.resize(n, 3);
        for (int i = 0; i < n; ++i) {
          out.t_s(i) = hand[static_cast<size_t>(from + i)].t_s - hand[static_cast<size_t>(from)].t_s;
          out.Y.row(i) = hand[static_cast<size_t>(from + i)].p_m.transpose();
        }
        segments.push_back(out);
      };
      make("reach", s.reachStartIndex, s.graspIndex);
      make("move", s.graspIndex, s.releaseIndex);
    }
  }
  return segments;
}

/// The table of one skill ("reach" or "move"): each variant's reproduction and adaptation errors over
/// the segments of that skill; `metrics` receives them per variant.
ResultTable skillTable(const std::string& skill, const std::vector<Segment>& segments, const std::vector<Variant>& vs,
                       const std::vector<std::vector<Outcome>>& outcomes, nlohmann::json& metrics)
{
  ResultTable table;
  table.title = "Section 8.4: " + skill + " DMPs (" +
                std::to_string(std::count_if(segments.begin(), segments.end(),
                                             [&](const Segment& s) { return s.skill == skill; })) +
                " demo segments, N = 20 basis functions)";
  table.columns = {"formulation", "thesis", "reproduction max error median / worst [mm]", "reproduction RMS median [mm]",
                   "adapted: goal error median / worst [mm]", "adapted: shape deviation median [mm]", "λ median"};
  for (size_t v = 0; v < vs.size(); ++v) {
    std::vector<double> repMax, repRms, goal, shape, lambda;
    for (size_t k = 0; k < segments.size(); ++k) {
      if (segments[k].skill != skill) continue;
      const Outcome& o = outcomes[v][k];
      repMax.push_back(o.reproductionMax_m);
      repRms.push_back(o.reproductionRms_m);
      goal.push_back(o.adaptedGoal_m);
      shape.push_back(o.adaptedShape_m);
      lambda.push_back(o.lambda);
    }
    std::string thesis = "—";
    if (v == 0 && skill == "reach") thesis = "fig. 8.6 (no number)";
    if (v == 1) thesis = skill == "reach" ? "fig. 8.7 (no number)" : "fig. 8.8 (no number)";
    table.rows.push_back({vs[v].name, thesis, mm(medianOf(repMax)) + " / " + mm(worst(repMax)), mm(medianOf(repRms)),
                          mm(medianOf(goal)) + " / " + mm(worst(goal)), mm(medianOf(shape)),
                          v == 4 ? formatNumber(medianOf(lambda) * 1e6, 2) + "e-6" : formatNumber(medianOf(lambda), 1)});
    metrics[vs[v].name] = {{"segments", repMax.size()},
                           {"reproduction_max_error_m", {{"median", medianOf(repMax)}, {"worst", worst(repMax)}}},
                           {"reproduction_rms_error_m", {{"median", medianOf(repRms)}}},
                           {"adapted_goal_error_m", {{"median", medianOf(goal)}, {"worst", worst(goal)}}},
                           {"adapted_shape_deviation_m", {{"median", medianOf(shape)}}},
                           {"lambda_median", medianOf(lambda)}};
  }
  table.note = "Thesis section 8.4 shows these DMPs in figs. 8.6-8.8 without numbers. Thesis formulation = "
               "dfki-ric movement_primitives as the thesis used it (start at rest, forcing term unscaled), "
               "reproduced by libs/motion's Reference mode. Adaptation: start +(5, -3, 2) cm, goal +(-4, 6, -1) cm, "
               "same duration; shape deviation = distance to the demo shifted by the time-blend of the two shifts.";
  return table;
}

}  // namespace

ExperimentResult runDmpExperiment(const ExperimentOptions& options)
{
  const WallClock clock;
  ExperimentResult result;
  result.name = "dmp";
  const auto dir = experimentDirOf(options, result.name);
  const int count = demoCountOf(options);
  const motion::AdaptationShift shift;
  const auto vs = variants();

  // Reach and Move segments of every moved object (as SkillLearner learns them).
  const std::vector<Segment> segments = demoSegments(options, count, result.name);
  if (segments.empty())
    throw core::InvalidInputError("dmp: the demos gave no Reach/Move segment (no object was found moving)");
  reportProgress(options, "dmp: learning " + std::to_string(segments.size() * vs.size()) + " DMPs", 0.95);

  // outcomes[v][k]: variant v on segment k.
  std::vector<std::vector<Outcome>> outcomes(vs.size());
  for (size_t v = 0; v < vs.size(); ++v)
    for (const auto& s : segments) outcomes[v].push_back(evaluate(s, vs[v].config, shift));

  for (const std::string skill : {"reach", "move"})
    result.tables.push_back(skillTable(skill, segments, vs, outcomes, result.metrics[skill]));

  // Per segment, the thesis formulation with lambda = 0.1 against ours (GCV).
  ResultTable perSegment;
  perSegment.title = "Section 8.4: reproduction max error per segment [mm]";
  perSegment.columns = {"segment", "samples", "thesis", "thesis formulation λ = 0", "λ = 0.1", "ours GCV", "ours λ"};
  for (size_t k = 0; k < segments.size(); ++k) {
    perSegment.rows.push_back({segments[k].label, std::to_string(segments[k].t_s.size()), "—",
                               mm(outcomes[0][k].reproductionMax_m), mm(outcomes[1][k].reproductionMax_m),
                               mm(outcomes[4][k].reproductionMax_m), formatNumber(outcomes[4][k].lambda * 1e6, 2) + "e-6"});
  }
  perSegment.note = "The thesis formulation starts at rest while the demo segments start moving: most of its error is "
                    "the first samples; ours starts with the demo's velocity.";
  result.tables.push_back(perSegment);

  // Figures of the first object's segments, as the thesis shows them.
  const auto firstOf = [&](const std::string& skill) {
    for (size_t k = 0; k < segments.size(); ++k)
      if (segments[k].skill == skill) return k;
    return segments.size();
  };
  const size_t reach = firstOf("reach"), move = firstOf("move");
  if (reach < segments.size()) {
    const auto p6 = dir / "fig8_6_reach_lambda0.png", p7 = dir / "fig8_7_reach_lambda0.1.png";
    writeDmpFigure(p6.string(), "Reach DMP, lambda = 0, N = 20 (like thesis fig. 8.6): " + segments[reach].label, segments[reach],
                   outcomes[0][reach], outcomes[4][reach], shift);
    writeDmpFigure(p7.string(), "Reach DMP, lambda = 0.1, N = 20 (like thesis fig. 8.7): " + segments[reach].label,
                   segments[reach], outcomes[1][reach], outcomes[4][reach], shift);
    result.figures.push_back(p6);
    result.figures.push_back(p7);
  }
  if (move < segments.size()) {
    const auto p8 = dir / "fig8_8_move_lambda0.1.png";
    writeDmpFigure(p8.string(), "Move DMP, lambda = 0.1, N = 20 (like thesis fig. 8.8): " + segments[move].label,
                   segments[move], outcomes[1][move], outcomes[4][move], shift);
    result.figures.push_back(p8);
  }

  std::vector<double> thesisRep, oursRep;
  for (size_t k = 0; k < segments.size(); ++k) {
    thesisRep.push_back(outcomes[1][k].reproductionMax_m);
    oursRep.push_back(outcomes[4][k].reproductionMax_m);
  }
  result.summary = std::to_string(segments.size()) + " Reach/Move segments from " + std::to_string(count) +
                   " demos: reproduction max error median " + mm(medianOf(oursRep)) + " mm with ours (GCV) vs " +
                   mm(medianOf(thesisRep)) + " mm with the thesis formulation (λ = 0.1).";
  result.wallTime_s = clock.seconds();
  return result;
}

}  // namespace srp::experiment
