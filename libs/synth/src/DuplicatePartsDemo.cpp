#include "srp/synth/DuplicatePartsDemo.h"

#include <cmath>
#include <random>

#include "srp/core/Error.h"

namespace srp::synth {

DuplicatePartsDemo makeDuplicatePartsDemo(const srp::core::Scene& base, const srp::core::ObjectCatalogue& catalogue,
                                          std::uint32_t seed, const DuplicatePartsOptions& o) {
  const srp::core::ObjectClass& cls = catalogue.at(o.className);
  if (cls.kind != srp::core::ObjectKind::Part)
    throw srp::core::InvalidInputError("duplicate-parts demo: '" + o.className + "' is not a part class");
  const srp::core::SceneObject* target = base.findObject(o.targetId);
  if (!target)
    throw srp::core::InvalidInputError("duplicate-parts demo: the base scene '" + base.name + "' has no '" + o.targetId +
                                       "' to place into");
  DuplicatePartsDemo out;
  out.scene = base;
  out.scene.name = base.name + "-duplicates-" + std::to_string(seed);
  out.scene.seed = static_cast<int>(seed);
  out.scene.objects.clear();
  for (const auto& obj : base.objects)
    if (const auto* c = catalogue.find(obj.className); c && c->kind == srp::core::ObjectKind::Container)
      out.scene.objects.push_back(obj);

  std::mt19937 rng(seed);
  const auto uniform = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const Eigen::Vector2d start(uniform(o.startXMin_m, o.startXMax_m), uniform(o.startYMin_m, o.startYMax_m));
  const Eigen::Vector2d goal = target->X_world_object.translation().head<2>();
  const Eigen::Vector2d way = goal - start;
  const Eigen::Vector2d side = Eigen::Vector2d(-way.y(), way.x()).normalized();
  const double sign = uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
  const Eigen::Vector2d other = start + uniform(o.wayMin, o.wayMax) * way + sign * uniform(o.sideMin_m, o.sideMax_m) * side;
  const int moved = static_cast<int>(seed % 2);  // both colours moved over consecutive seeds

  const auto place = [&](const Eigen::Vector2d& p_xy, int colour) {
    srp::core::SceneObject s;
    std::string word = o.colours[colour];
    s.id = o.className + "_" + word;
    for (char& c : s.id)
      if (c == ' ') c = '_';
    s.className = o.className;
    s.colour = word;
    s.X_world_object = srp::core::Pose3::Identity();
    s.X_world_object.linear() = Eigen::AngleAxisd(uniform(-M_PI, M_PI), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    s.X_world_object.translation() = Eigen::Vector3d(p_xy.x(), p_xy.y(), 0.0);
    out.scene.objects.push_back(s);
    return s.id;
  };
  out.movedId = place(start, moved);
  out.otherId = place(other, 1 - moved);
  out.scene.validate(catalogue);

  const std::string noun = o.className, colour = o.colours[moved];
  const srp::core::ObjectClass& targetClass = catalogue.at(target->className);
  const std::string targetColour = srp::core::instanceColour(*target, targetClass);
  const std::string targetNoun = targetClass.noun.empty() ? targetClass.name : targetClass.noun;
  out.plan = {{"instruction", "Pick up the " + colour + " " + noun + " and place it in the " +
                                  (targetColour.empty() ? "" : targetColour + " ") + targetNoun + "."},
              {"steps", nlohmann::json::array({{{"object", {{"name", noun}, {"color", colour}}},
                                                {"source", nlohmann::json::array()},
                                                {"target", nlohmann::json::array({{{"relation", "in"},
                                                                                   {"landmark", {{"name", targetNoun},
                                                                                                 {"color", targetColour.empty() ? nlohmann::json(nullptr) : nlohmann::json(targetColour)}}}}})}}})}};
  return out;
}

}  // namespace srp::synth
