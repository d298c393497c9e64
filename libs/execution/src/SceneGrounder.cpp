#include "srp/execution/SceneGrounder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "srp/core/Text.h"
#include "srp/core/Scene.h"
#include "srp/core/SpatialRelations.h"

namespace srp::execution {
namespace {

std::string normalise(std::string s) {
  s = srp::core::normaliseName(std::move(s));
  for (std::size_t p; (p = s.find("grey")) != std::string::npos;) s.replace(p, 4, "gray");
  return s;
}

bool endsWithWord(const std::string& s, const std::string& word) {
  return s.size() > word.size() && s.compare(s.size() - word.size(), word.size(), word) == 0 &&
         s[s.size() - word.size() - 1] == ' ';
}

/// The colour word an instance answers to (rule 2).
std::string colourOf(const CellObject& o) {
  return normalise(o.colour.empty() ? srp::core::nearestColourName(o.rgb) : o.colour);
}

bool nameFits(const CellObject& o, const std::string& name) {
  const std::string id = normalise(o.name), cls = normalise(o.className), noun = normalise(o.noun);
  auto fits = [&](const std::string& n) {
    return !n.empty() && (n == noun || n == cls || n == id || endsWithWord(cls, n) || endsWithWord(id, n));
  };
  if (fits(name)) return true;
  // Plurals: "the stars", "the boxes".
  if (name.size() > 3 && name.compare(name.size() - 2, 2, "es") == 0 && fits(name.substr(0, name.size() - 2))) return true;
  return name.size() > 2 && name.back() == 's' && fits(name.substr(0, name.size() - 1));
}

bool colourFits(const CellObject& o, const std::string& name, const std::string& colour) {
  return colourOf(o) == colour || normalise(o.className) == colour + " " + name || normalise(o.name) == colour + " " + name;
}

std::string plural(const std::string& noun) {
  if (noun.empty()) return noun;
  const char last = noun.back();
  return noun + ((last == 's' || last == 'x' || last == 'h') ? "es" : "s");
}

std::string countWord(std::size_t n) {
  static const char* kWords[] = {"no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten"};
  return n <= 10 ? kWords[n] : std::to_string(n);
}

std::string listInstances(const std::vector<const CellObject*>& objects) {
  std::string s;
  for (std::size_t i = 0; i < objects.size(); ++i)
    s += (i == 0 ? "" : i + 1 == objects.size() ? " and " : ", ") + SceneGrounder::describeInstance(*objects[i]);
  return s;
}

std::vector<std::string> idsOf(const std::vector<const CellObject*>& objects) {
  std::vector<std::string> ids;
  for (const auto* o : objects) ids.push_back(o->name);
  return ids;
}

Eigen::Vector2d centre(const CellObject& o) { return o.X_world_object.translation().head<2>(); }

/// Half-width of an object's footprint along world direction d (unit).
double support(const CellObject& o, const Eigen::Vector2d& d) {
  const Eigen::Vector2d ax = o.X_world_object.linear().col(0).head<2>().normalized();
  const Eigen::Vector2d ay = o.X_world_object.linear().col(1).head<2>().normalized();
  return std::abs(d.dot(ax)) * o.size_m.x() / 2 + std::abs(d.dot(ay)) * o.size_m.y() / 2;
}

enum class RelationKind { In, On, Under, Direction, Near, Closest, Farthest, Unknown };

struct ParsedRelation {
  RelationKind kind = RelationKind::Unknown;
  std::string direction;  ///< "left", "right", "front", "behind" for Direction
};

ParsedRelation parseRelation(const std::string& relationIn) {
  std::string r = normalise(relationIn);
  for (const std::string prefix : {"to the ", "on the ", "at the ", "back to ", "back in ", "back into "})
    if (r.rfind(prefix, 0) == 0 && r.size() > prefix.size()) {
      const std::string rest = r.substr(prefix.size());
      if (rest.rfind("left", 0) == 0 || rest.rfind("right", 0) == 0 || rest.rfind("back", 0) == 0 ||
          prefix.rfind("back", 0) == 0)
        r = rest;
    }
  if (r == "left of" || r == "left") return {RelationKind::Direction, "left"};
  if (r == "right of" || r == "right") return {RelationKind::Direction, "right"};
  if (r == "in front of" || r == "front of") return {RelationKind::Direction, "front"};
  if (r == "behind" || r == "in back of" || r == "back of") return {RelationKind::Direction, "behind"};
  if (r == "closest to" || r == "nearest to" || r == "closest" || r == "nearest") return {RelationKind::Closest, ""};
  if (r == "farthest from" || r == "furthest from") return {RelationKind::Farthest, ""};
  if (r == "on top of" || r == "atop" || r == "above" || r == "over" || r == "off" || r == "off of")
    return {RelationKind::On, ""};
  if (r == "under" || r == "below" || r == "underneath" || r == "beneath") return {RelationKind::Under, ""};
  if (r == "from" || r == "out of" || r == "from inside" || r == "inside of" || r == "inside" || r == "within" ||
      srp::core::isContainmentRelation(r))
    return {RelationKind::In, ""};
  if (srp::core::isNeighbourRelation(r)) return {RelationKind::Near, ""};
  return {};
}

constexpr const char* kKnownRelations =
    "in, into, inside, from, out of, on, on top of, off, under, left of, right of, in front of, behind, next to, "
    "beside, near, closest to, farthest from";

/// Keeps the objects of `current` whose `score` is within `tol` of the largest (or smallest) one.
void keepExtreme(std::vector<const CellObject*>& current, const std::function<double(const CellObject&)>& score,
                 bool largest, double tol) {
  double best = largest ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  for (const auto* o : current) best = largest ? std::max(best, score(*o)) : std::min(best, score(*o));
  std::vector<const CellObject*> kept;
  for (const auto* o : current)
    if (std::abs(score(*o) - best) <= tol) kept.push_back(o);
  current = kept;
}

/// 4b. The phrase's superlative ("leftmost", "biggest", ...): keeps the objects of `current` at the
/// extreme (within `tol`; 10 % of the largest volume for sizes, seen from `view`).
void keepSuperlative(std::vector<const CellObject*>& current, const std::string& sup, const std::string& phrase,
                     const srp::core::ViewFrame& view, double tol) {
  auto top = [](const CellObject& o) { return o.X_world_object.translation().z() + o.size_m.z(); };
  auto volume = [](const CellObject& o) { return o.size_m.prod(); };
  auto right = [&](const CellObject& o) { return view.rightOf(o.X_world_object.translation()); };
  auto front = [&](const CellObject& o) { return view.frontOf(o.X_world_object.translation()); };
  if (sup == "leftmost") keepExtreme(current, right, false, tol);
  else if (sup == "rightmost") keepExtreme(current, right, true, tol);
  else if (sup == "frontmost" || sup == "closest") keepExtreme(current, front, true, tol);
  else if (sup == "backmost" || sup == "farthest") keepExtreme(current, front, false, tol);
  else if (sup == "highest") keepExtreme(current, top, true, tol);
  else if (sup == "lowest") keepExtreme(current, top, false, tol);
  else if (sup == "biggest" || sup == "smallest") {
    double largest = 0.0;
    for (const auto* o : current) largest = std::max(largest, volume(*o));
    keepExtreme(current, volume, sup == "biggest", 0.1 * largest);
  } else {
    throw GroundingError("unknown superlative '" + sup + "' in " + phrase +
                             " (known: leftmost, rightmost, frontmost, backmost, closest, farthest, biggest, "
                             "smallest, highest, lowest)",
                         idsOf(current));
  }
}

/// 5. The phrase's ordinal, counted left to right in `view` (objects within `tol` of the one counted
/// tie): keeps those of `current`; else says why none fits.
std::string keepOrdinal(std::vector<const CellObject*>& current, const ObjectReference& ref, const std::string& phrase,
                        const srp::core::ViewFrame& view, double tol) {
  std::vector<const CellObject*> ordered = current;
  auto right = [&](const CellObject* o) { return view.rightOf(o->X_world_object.translation()); };
  std::stable_sort(ordered.begin(), ordered.end(), [&](const auto* a, const auto* b) { return right(a) < right(b); });
  const int n = static_cast<int>(ordered.size());
  const int index = *ref.ordinal == -1 ? n - 1 : *ref.ordinal - 1;
  if (index < 0 || index >= n)
    return phrase + ": only " + countWord(ordered.size()) + " " + (ordered.size() == 1 ? ref.name : plural(ref.name)) +
           " fit (" + listInstances(ordered) + "), counted left to right";
  std::vector<const CellObject*> kept;
  for (const auto* o : ordered)
    if (std::abs(right(o) - right(ordered[static_cast<std::size_t>(index)])) <= tol) kept.push_back(o);
  current = kept;
  return "";
}

}  // namespace

SceneGrounder::SceneGrounder(const CellDescription& scene, Options options)
    : scene_(scene), options_(options), view_(scene.viewFrame(options.viewpoint)) {}

std::string SceneGrounder::describeInstance(const CellObject& o) {
  char buf[64];
  std::snprintf(buf, sizeof buf, " at (%.3f, %.3f)", o.X_world_object.translation().x(),
                o.X_world_object.translation().y());
  return "'" + o.name + "'" + buf;
}

bool SceneGrounder::holds(const std::string& relation, const CellObject& o, const CellObject& l) const {
  const ParsedRelation r = parseRelation(relation);
  auto on = [&](const CellObject& top, const CellObject& bottom) {
    const Eigen::Vector3d p = bottom.X_world_object.inverse() * top.X_world_object.translation();
    return std::abs(p.x()) <= bottom.size_m.x() / 2 && std::abs(p.y()) <= bottom.size_m.y() / 2 &&
           p.z() >= bottom.size_m.z() - options_.onTolerance_m;
  };
  switch (r.kind) {
    case RelationKind::In:
      return l.kind == CellObjectKind::Container ? isInside(o, l) : on(o, l);
    case RelationKind::On:
      return l.kind == CellObjectKind::Container ? isInside(o, l) : on(o, l);
    case RelationKind::Under:
      return on(l, o);
    case RelationKind::Direction: {
      const Eigen::Vector2d d = centre(o) - centre(l);
      const Eigen::Vector2d dir = *view_.direction(r.direction);
      const Eigen::Vector2d perp(-dir.y(), dir.x());
      return d.dot(dir) > 0.0 && d.dot(dir) >= std::abs(d.dot(perp));
    }
    case RelationKind::Near: {
      const Eigen::Vector2d d = centre(o) - centre(l);
      if (d.norm() < 1e-9) return true;
      const Eigen::Vector2d u = d.normalized();
      return d.norm() - support(o, u) - support(l, u) <= options_.nearGap_m;
    }
    case RelationKind::Closest:
    case RelationKind::Farthest:
      return true;  // a superlative: it ranks, it does not filter
    case RelationKind::Unknown:
      break;
  }
  throw srp::core::InvalidInputError("unknown spatial relation '" + relation + "' in a noun phrase (known: " +
                                     kKnownRelations + ")");
}

SceneGrounder::Selection SceneGrounder::select(const ObjectReference& ref, const std::vector<SpatialRelation>& where,
                                               std::optional<CellObjectKind> kind) const {
  Selection out;
  const std::string name = normalise(ref.name);
  const std::string phrase = "'the " + ref.describe() + "'";
  // 1. name
  std::vector<const CellObject*> named;
  for (const auto& o : scene_.objects)
    if ((!kind || o.kind == *kind) && nameFits(o, name)) named.push_back(&o);
  if (named.empty()) {
    std::vector<const CellObject*> all;
    for (const auto& o : scene_.objects) all.push_back(&o);
    out.whyNone = "no " + ref.name + " in the scene for " + phrase + " (the scene holds " + listInstances(all) + ")";
    return out;
  }
  // 2. colour
  std::vector<const CellObject*> coloured;
  if (ref.colour) {
    const std::string colour = normalise(*ref.colour);
    for (const auto* o : named)
      if (colourFits(*o, name, colour)) coloured.push_back(o);
    if (coloured.empty()) {
      std::string seen;
      for (const auto* o : named) seen += (seen.empty() ? "" : ", ") + colourOf(*o) + " " + describeInstance(*o);
      out.whyNone = "no " + *ref.colour + " " + ref.name + " in the scene for " + phrase + " (" + plural(ref.name) +
                    " there: " + seen + ")";
      return out;
    }
  } else {
    coloured = named;
  }
  // 3. relations; superlative relations are kept for 4.
  std::vector<SpatialRelation> relations = ref.relations;
  relations.insert(relations.end(), where.begin(), where.end());
  std::vector<const CellObject*> current = coloured;
  std::vector<std::pair<ParsedRelation, std::vector<const CellObject*>>> rankings;
  for (const auto& rel : relations) {
    const ParsedRelation parsed = parseRelation(rel.relation);
    if (parsed.kind == RelationKind::Unknown)
      throw GroundingError("unknown spatial relation '" + rel.relation + "' in " + phrase + " (known: " +
                               kKnownRelations + ")",
                           idsOf(current));
    const Selection landmarks = select(rel.landmark, {}, std::nullopt);
    if (landmarks.objects.empty()) {
      out.whyNone = "the landmark of '" + rel.relation + " the " + rel.landmark.describe() + "' in " + phrase +
                    ": " + landmarks.whyNone;
      return out;
    }
    if (parsed.kind == RelationKind::Closest || parsed.kind == RelationKind::Farthest) {
      rankings.push_back({parsed, landmarks.objects});
      continue;
    }
    std::vector<const CellObject*> kept;
    for (const auto* o : current)
      if (std::any_of(landmarks.objects.begin(), landmarks.objects.end(),
                      [&](const CellObject* l) { return l != o && holds(rel.relation, *o, *l); }))
        kept.push_back(o);
    if (kept.empty()) {
      const std::string what = ref.colour ? *ref.colour + " " + ref.name : ref.name;
      out.whyNone = "no " + what + " is " + rel.relation + " the " + rel.landmark.describe() + " for " + phrase +
                    " (" + plural(what) + " there: " + listInstances(current) + "; " +
                    plural(rel.landmark.describe()) + ": " + listInstances(landmarks.objects) + ")";
      return out;
    }
    current = kept;
  }
  // 4. superlatives: keep everything within the tolerance of the extreme.
  for (const auto& [parsed, landmarks] : rankings) {
    auto distance = [&, lms = landmarks](const CellObject& o) {
      double d = std::numeric_limits<double>::infinity();
      for (const auto* l : lms)
        if (l != &o) d = std::min(d, (centre(o) - centre(*l)).norm());
      return d;
    };
    keepExtreme(current, distance, parsed.kind == RelationKind::Farthest, options_.tieTolerance_m);
  }
  if (!ref.superlative.empty()) keepSuperlative(current, ref.superlative, phrase, view_, options_.tieTolerance_m);
  // 5. ordinal: left to right in the view frame.
  if (ref.ordinal) {
    out.whyNone = keepOrdinal(current, ref, phrase, view_, options_.tieTolerance_m);
    if (!out.whyNone.empty()) return out;
  }
  out.objects = current;
  return out;
}

std::vector<const CellObject*> SceneGrounder::candidates(const ObjectReference& ref,
                                                         const std::vector<SpatialRelation>& where,
                                                         std::optional<CellObjectKind> kind) const {
  return select(ref, where, kind).objects;
}

const CellObject& SceneGrounder::ground(const ObjectReference& ref, const std::vector<SpatialRelation>& where,
                                        std::optional<CellObjectKind> kind) const {
  const Selection s = select(ref, where, kind);
  if (s.objects.empty()) throw GroundingError(s.whyNone, {});
  if (s.objects.size() > 1) {
    const std::string what = ref.colour ? *ref.colour + " " + ref.name : ref.name;
    throw GroundingError(countWord(s.objects.size()) + " " + plural(what) + " match 'the " + ref.describe() +
                             "': " + listInstances(s.objects) +
                             " (world x, y in m); say which (e.g. by colour, 'the leftmost', 'the second' counted "
                             "left to right, or 'the " + ref.name + " next to the ...')",
                         idsOf(s.objects));
  }
  return *s.objects.front();
}

std::vector<std::string> groundingProblems(const ExecutionPlan& plan, const CellDescription& scene,
                                           const SceneGrounder::Options& options) {
  const SceneGrounder grounder(scene, options);
  std::vector<std::string> problems;
  std::vector<std::string> moved;  // instances earlier steps move (by name fit: they may be anywhere then)
  auto touchesMoved = [&](const ObjectReference& ref) {
    const ObjectReference bare{ref.name, ref.colour, std::nullopt, {}, {}};
    for (const auto* o : grounder.candidates(bare))
      if (std::find(moved.begin(), moved.end(), o->name) != moved.end()) return true;
    return false;
  };
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    const ExecutionStep& step = plan.steps[i];
    const std::string prefix = "step " + std::to_string(i + 1) + " ('the " + step.object.describe() + "'): ";
    bool dependsOnEarlierSteps = !moved.empty() && touchesMoved(step.object);
    for (const auto& r : step.source) dependsOnEarlierSteps |= !moved.empty() && touchesMoved(r.landmark);
    for (const auto& r : step.object.relations) dependsOnEarlierSteps |= !moved.empty() && touchesMoved(r.landmark);
    try {
      const CellObject& part = grounder.ground(step.object, step.source, CellObjectKind::Part);
      for (const auto& rel : step.target) {
        if (!moved.empty() && touchesMoved(rel.landmark)) continue;
        if (rel.relation.rfind("between", 0) == 0) {
          // "between the stars": a plural landmark; "between A and B": A and B each one instance.
          if (rel.secondLandmark) {
            for (const ObjectReference* l : {&rel.landmark, &*rel.secondLandmark}) {
              try {
                grounder.ground(*l);
              } catch (const GroundingError& e) {
                throw GroundingError("target 'between' the " + l->describe() + ": " + e.what(), e.candidates());
              }
            }
          } else if (grounder.candidates(rel.landmark).empty()) {
            grounder.ground(rel.landmark);  // throws the reason
          }
          continue;
        }
        // Any kind: "on the star" stacks on a part, "in the box" names a container anyway;
        // whether the relation fits the landmark is PlacementPlanner's to say.
        try {
          grounder.ground(rel.landmark);
        } catch (const GroundingError& e) {
          throw GroundingError("target '" + rel.relation + " the " + rel.landmark.describe() + "': " + e.what(),
                               e.candidates());
        }
      }
      moved.push_back(part.name);
    } catch (const GroundingError& e) {
      if (!dependsOnEarlierSteps) problems.push_back(prefix + e.what());
      // The executor grounds the step again when its turn comes; what it may move is unknown here.
      for (const auto* o : grounder.candidates(ObjectReference{step.object.name, step.object.colour, std::nullopt, {}, {}}))
        moved.push_back(o->name);
    }
  }
  return problems;
}

}  // namespace srp::execution
