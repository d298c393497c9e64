#include "srp/motion/SkillPlots.h"

#include <sstream>

#include "srp/plot/Figure.h"

namespace srp::motion {
namespace {

void plotDmp(plot::Axes& ax, const Segmentation& seg, int from, const Dmp& learned, const AdaptationShift& shift,
             const std::string& title) {
  Dmp dmp = learned;
  const DmpRollout rep = dmp.rollout();
  dmp.configure(dmp.demoStart() + shift.start_m, dmp.demoGoal() + shift.goal_m);
  const DmpRollout ad = dmp.rollout();
  const char* axisName[3] = {"x", "y", "z"};
  double worst = 0.0;
  for (int k = 0; k < 3; ++k) {
    std::vector<double> t, demo, r, a;
    for (Eigen::Index i = 0; i < rep.y.rows(); ++i) {
      const auto& s = seg.hand[static_cast<std::size_t>(from + i)];
      t.push_back(rep.t_s(i));
      demo.push_back(s.p_m(k));
      r.push_back(rep.y(i, k));
      a.push_back(ad.y(i, k));
      worst = std::max(worst, (rep.y.row(i).transpose() - s.p_m).norm());
    }
    ax.line(t, demo, std::string("demo ") + axisName[k], plot::Colour::tab(k), 3.0);
    ax.line(t, r, std::string("reproduction ") + axisName[k], plot::Colour::tab(k + 3), 1.5, true);
    ax.line(t, a, std::string("adapted ") + axisName[k], plot::Colour::tab(k + 6), 1.5);
  }
  std::ostringstream os;
  os << title << " (lambda " << learned.lambda() << ", max " << worst * 1e3 << " mm)";
  ax.title = os.str();
  ax.xLabel = "t [s]";
  ax.yLabel = "position [m]";
}

}  // namespace

void writeSkillFigure(const std::string& pngPath, const Segmentation& seg, const ObjectSegmentation& o,
                      const SkillSet& s, const AdaptationShift& shift) {
  plot::Figure fig(1400, 1000, 2, 2);
  fig.title = "Object '" + o.name + "': segmentation and skills";
  auto& traj = fig.axes(0, 0);
  traj.title = "Object trajectory by mixture component";
  traj.xLabel = "t [s]";
  traj.yLabel = "position [m]";
  const char* axisName[3] = {"x", "y", "z"};
  const plot::Marker markers[3] = {plot::Marker::Circle, plot::Marker::Square, plot::Marker::Triangle};
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3; ++k) {
      std::vector<double> t, v;
      for (std::size_t i = 0; i < o.smoothed.size(); ++i)
        if (o.component[i] == c) t.push_back(o.smoothed[i].t_s), v.push_back(o.smoothed[i].p_m(k));
      if (!t.empty())
        traj.scatter(t, v, k == 0 ? "component " + std::to_string(c) : "", plot::Colour::tab(c), markers[k], 3.0);
    }
  for (int k = 0; k < 3; ++k) {
    std::vector<double> t, v;
    for (const auto& smp : o.smoothed.samples()) t.push_back(smp.t_s), v.push_back(smp.p_m(k));
    traj.line(t, v, k == 0 ? "x/y/z (o/square/triangle)" : "", plot::Colour::gray(), 0.8);
  }
  (void)axisName;
  traj.verticalLine(seg.hand[static_cast<std::size_t>(o.graspIndex)].t_s, "grasp", plot::Colour::tab(3));
  traj.verticalLine(seg.hand[static_cast<std::size_t>(o.releaseIndex)].t_s, "release", plot::Colour::tab(4));

  auto& dist = fig.axes(0, 1);
  dist.title = "Hand distance to the object's initial position";
  dist.xLabel = "t [s]";
  dist.yLabel = "distance [m]";
  std::vector<double> t, d;
  for (const auto& h : seg.hand.samples()) t.push_back(h.t_s), d.push_back((h.p_m - o.p_initial_m).norm());
  dist.line(t, d, "|hand - initial position|");
  dist.verticalLine(seg.hand[static_cast<std::size_t>(o.searchStartIndex)].t_s, "search start", plot::Colour::gray());
  dist.verticalLine(seg.hand[static_cast<std::size_t>(o.graspIndex)].t_s, "grasp", plot::Colour::tab(3));
  dist.verticalLine(seg.hand[static_cast<std::size_t>(o.releaseIndex)].t_s, "release", plot::Colour::tab(4));

  if (s.reach) plotDmp(fig.axes(1, 0), seg, s.reachStartIndex, *s.reach, shift, "Reach");
  if (s.move) plotDmp(fig.axes(1, 1), seg, s.graspIndex, *s.move, shift, "Move");
  fig.save(pngPath);
}

}  // namespace srp::motion
