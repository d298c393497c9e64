#include "srp/execution/PlanConversion.h"

#include <algorithm>
#include <sstream>
#include <cctype>
#include <iterator>
#include <tuple>
#include <map>

#include "srp/core/Text.h"
#include "srp/core/Error.h"

namespace srp::execution {
namespace {

bool isSourceWord(const std::string& d) { return d == "from" || d == "out of" || d == "off" || d == "from inside"; }

ObjectReference refOf(const srp::taskdb::ProductRow& p) { return {p.objectName, p.colour, std::nullopt, {}, {}}; }

bool sameRelation(const SpatialRelation& a, const SpatialRelation& b) {
  return a.relation == b.relation && a.landmark.name == b.landmark.name && a.landmark.colour == b.landmark.colour;
}

void addUnique(std::vector<SpatialRelation>& list, const SpatialRelation& r) {
  if (std::none_of(list.begin(), list.end(), [&](const auto& x) { return sameRelation(x, r); })) list.push_back(r);
}

}  // namespace

ExecutionPlan planFromTaskModel(const srp::taskdb::TaskModel& model, const std::optional<srp::core::Pose3>& X_world_camera) {
  const std::string context = "task model " + std::to_string(model.info.id) + " ('" + model.info.name + "')";
  auto product = [&](int id) -> const srp::taskdb::ProductRow& {
    const auto* p = model.findProduct(id);
    if (!p) throw srp::core::InvalidInputError(context + ": no product with ObjectId " + std::to_string(id));
    return *p;
  };
  std::map<int, const srp::taskdb::SourceLocationRow*> sources;
  std::map<int, const srp::taskdb::TargetLocationRow*> targets;
  for (const auto& s : model.sourceLocations) sources[s.locationId] = &s;
  for (const auto& t : model.targetLocations) targets[t.locationId] = &t;

  ExecutionPlan plan;
  std::vector<std::vector<int>> sentencesOfStep;
  std::map<std::string, std::size_t> stepOfName;
  std::vector<bool> sourceUsed(0), targetUsed(0);
  std::map<int, bool> usedSource, usedTarget;
  auto addRelation = [&](ExecutionStep& step, const std::string& description, int landmarkId) {
    const SpatialRelation r{description, refOf(product(landmarkId)), std::nullopt, {}};
    addUnique(isSourceWord(description) ? step.source : step.target, r);
  };
  for (int objectId : model.targetObjectIds) {
    const auto& p = product(objectId);
    auto it = stepOfName.find(p.objectName);
    if (it == stepOfName.end()) {
      it = stepOfName.emplace(p.objectName, plan.steps.size()).first;
      plan.steps.push_back({refOf(p), {}, {}, {}, {}});
      sentencesOfStep.emplace_back();
    }
    ExecutionStep& step = plan.steps[it->second];
    if (p.sentenceId) sentencesOfStep[it->second].push_back(*p.sentenceId);
    if (p.sourceLocationId) {
      const auto s = sources.find(*p.sourceLocationId);
      if (s == sources.end())
        throw srp::core::InvalidInputError(context + ": product " + std::to_string(objectId) +
                                           " refers to a missing SourceLocation " + std::to_string(*p.sourceLocationId));
      addRelation(step, s->second->description, s->second->trajectorObjectId);
      usedSource[s->first] = true;
    }
    if (p.targetLocationId) {
      const auto t = targets.find(*p.targetLocationId);
      if (t == targets.end())
        throw srp::core::InvalidInputError(context + ": product " + std::to_string(objectId) +
                                           " refers to a missing TargetLocation " + std::to_string(*p.targetLocationId));
      addRelation(step, t->second->description, t->second->indicatorObjectId);
      usedTarget[t->first] = true;
    }
  }
  // Locations no target object refers to join the step of their landmark's sentence.
  auto attachOrphan = [&](const std::string& description, int landmarkId) {
    const auto& lm = product(landmarkId);
    if (!lm.sentenceId) return;
    for (std::size_t i = 0; i < plan.steps.size(); ++i)
      if (std::count(sentencesOfStep[i].begin(), sentencesOfStep[i].end(), *lm.sentenceId) &&
          lm.objectName != plan.steps[i].object.name) {
        addRelation(plan.steps[i], description, landmarkId);
        return;
      }
  };
  for (const auto& s : model.sourceLocations)
    if (!usedSource.count(s.locationId)) attachOrphan(s.description, s.trajectorObjectId);
  for (const auto& t : model.targetLocations)
    if (!usedTarget.count(t.locationId)) attachOrphan(t.description, t.indicatorObjectId);

  if (X_world_camera) attachDemoOffsets(plan, model, *X_world_camera);
  return plan;
}

void attachDemoOffsets(ExecutionPlan& plan, const srp::taskdb::TaskModel& model, const srp::core::Pose3& X_world_camera) {
  if (model.productPoses.empty()) return;
  {
    auto classOf = [&](const ObjectReference& ref) -> std::optional<int> {
      for (const auto& g : model.groundedProducts)
        if (g.objectName == ref.name || g.objectName == (ref.colour ? *ref.colour + ref.name : ref.name) ||
            g.objectName == (ref.colour ? *ref.colour + " " + ref.name : ref.name))
          return g.classId;
      for (const auto& p : model.products)
        if (p.objectName == ref.name && p.classId && (!ref.colour || p.colour == ref.colour)) return p.classId;
      return std::nullopt;
    };
    auto finalPosition = [&](int classId) -> std::optional<Eigen::Vector3d> {
      const srp::taskdb::ProductPoseRow* last = nullptr;
      for (const auto& r : model.productPoses)
        if (r.classId == classId && (!last || r.timeId > last->timeId)) last = &r;
      if (!last) return std::nullopt;
      return last->p_m;
    };
    for (auto& step : plan.steps) {
      for (const auto& r : step.target) {
        if (!isNeighbourRelation(r.relation)) continue;
        const auto a = classOf(step.object), b = classOf(r.landmark);
        if (!a || !b) continue;
        const auto pa = finalPosition(*a), pb = finalPosition(*b);
        if (!pa || !pb) continue;
        const Eigen::Vector3d d_world = X_world_camera.linear() * (*pa - *pb);
        if (d_world.head<2>().norm() > 1e-3) step.demoOffsetFromNeighbour_m = d_world.head<2>();
      }
    }
  }
}

namespace {

// --- Spatial phrases the language model reads only in part ("to the left of the X"
// gives landmark "left"; "between A and B" gives only A; "right of the X" and "in the
// front left corner of X" give no target). They are re-read from the sentence's tokens.

bool isColourWord(const std::string& w) {
  static const char* kWords[] = {"red", "green", "blue", "yellow", "gray", "grey", "black", "white",
                                 "orange", "purple", "pink", "brown", "violet", "cyan", "magenta"};
  return std::any_of(std::begin(kWords), std::end(kWords), [&](const char* c) { return w == c; });
}

bool isViewWord(const std::string& w) {
  return w == "left" || w == "right" || w == "front" || w == "back" || w == "rear" || w == "top";
}

/// A noun phrase "[the|a|an] [colour] noun" starting at token i; the index after it.
std::optional<std::pair<ObjectReference, std::size_t>> nounPhraseAt(const std::vector<std::string>& tokens, std::size_t i) {
  while (i < tokens.size() && (tokens[i] == "the" || tokens[i] == "a" || tokens[i] == "an")) ++i;
  ObjectReference ref;
  if (i < tokens.size() && isColourWord(tokens[i])) ref.colour = tokens[i++];
  if (i >= tokens.size() || !std::isalpha(static_cast<unsigned char>(tokens[i][0])) || tokens[i] == "and" ||
      tokens[i] == "of")
    return std::nullopt;
  ref.name = tokens[i];
  return std::make_pair(ref, i + 1);
}

/// The relation named by view words before "of" ("left" -> "left of", "front" -> "in front of").
std::string viewRelation(const std::string& w) {
  if (w == "left" || w == "right") return w + " of";
  if (w == "front") return "in front of";
  if (w == "back" || w == "rear") return "behind";
  return "on top of";
}

/// The first spatial phrase in tokens [from, end): the relation and the token range it spans.
struct TokenRelation {
  SpatialRelation relation;
  std::size_t begin = 0, end = 0;
};
std::optional<TokenRelation> spatialPhraseIn(const std::vector<std::string>& t, std::size_t from) {
  for (std::size_t i = from; i < t.size(); ++i) {
    // "in the front left corner of the gray box"
    if (t[i] == "corner" && i + 1 < t.size() && t[i + 1] == "of") {
      std::string corner;
      std::size_t b = i;
      while (b > from && isViewWord(t[b - 1]) && t[b - 1] != "top") corner = t[--b] + (corner.empty() ? "" : " ") + corner;
      const auto np = nounPhraseAt(t, i + 2);
      if (!corner.empty() && np) {
        while (b > from && (t[b - 1] == "the" || t[b - 1] == "in" || t[b - 1] == "at" || t[b - 1] == "into")) --b;
        TokenRelation r{{"corner", np->first, std::nullopt, corner}, b, np->second};
        return r;
      }
    }
    // "(to|on|at) the left of X", "right of X", "in front of X", "on top of X"
    if (isViewWord(t[i]) && i + 1 < t.size() && t[i + 1] == "of") {
      if (const auto np = nounPhraseAt(t, i + 2)) {
        std::size_t b = i;
        while (b > from && (t[b - 1] == "the" || t[b - 1] == "to" || t[b - 1] == "on" || t[b - 1] == "in" ||
                            t[b - 1] == "at"))
          --b;
        return TokenRelation{{viewRelation(t[i]), np->first, std::nullopt, ""}, b, np->second};
      }
    }
    if (t[i] == "behind")
      if (const auto np = nounPhraseAt(t, i + 1)) return TokenRelation{{"behind", np->first, std::nullopt, ""}, i, np->second};
    // "between A and B"
    if (t[i] == "between")
      if (const auto a = nounPhraseAt(t, i + 1); a && a->second < t.size() && t[a->second] == "and")
        if (const auto b = nounPhraseAt(t, a->second + 1))
          return TokenRelation{{"between", a->first, b->first, ""}, i, b->second};
  }
  return std::nullopt;
}

}  // namespace

ExecutionPlan planFromLanguage(const srp::language::TaskPlan& plan) {
  auto tokensOf = [&](int sentence) -> std::vector<std::string> {
    std::vector<std::string> t;
    if (sentence < 0 || sentence >= static_cast<int>(plan.sentences.size())) return t;
    for (const auto& w : plan.sentences[static_cast<std::size_t>(sentence)].tokens) t.push_back(srp::core::toLowerAscii(w));
    return t;
  };
  ExecutionPlan out;
  // Token spans (sentence, begin, end) taken by re-read relations: a "step" whose object
  // lies inside one ("corner" of "in the front left corner of the box") is a misread.
  std::vector<std::tuple<int, std::size_t, std::size_t>> consumed;
  std::vector<int> objectSentence, objectToken;
  for (const auto& s : plan.steps) {
    ExecutionStep step;
    // One type (language::ObjectRef): colour, ordinal, superlative and the
    // noun phrase's own relations reach SceneGrounder unchanged.
    step.object = s.object;
    for (const auto& l : s.source) step.source.push_back(l);
    for (std::size_t k = 0; k < s.target.size(); ++k) {
      const auto& l = s.target[k];
      SpatialRelation r = l;
      const srp::language::TokenAnchor anchor = k < s.targetAnchors.size() ? s.targetAnchors[k] : srp::language::TokenAnchor{};
      const std::vector<std::string> t = tokensOf(anchor.sentenceId);
      if (anchor.tokenId >= 0 && static_cast<std::size_t>(anchor.tokenId) < t.size()) {
        const std::size_t i = static_cast<std::size_t>(anchor.tokenId);
        const bool viewLandmark = isViewWord(srp::core::toLowerAscii(l.landmark.name)) && !l.landmark.colour;
        const bool lonelyBetween = srp::core::toLowerAscii(l.relation) == "between" && !l.secondLandmark;
        // A whole view phrase read by the language model ("to the left of", "in the front left
        // corner of") is re-read too, into the same relation as above ("left of", "corner").
        std::size_t relationWords = 0;
        bool viewPhrase = false;
        {
          std::istringstream words(srp::core::toLowerAscii(l.relation));
          for (std::string w; words >> w; ++relationWords) viewPhrase |= isViewWord(w) || w == "corner";
          viewPhrase = viewPhrase && relationWords > 1;
        }
        if (viewLandmark || lonelyBetween || viewPhrase) {
          // Re-read from the relation word before the landmark.
          const std::size_t back = viewPhrase ? relationWords + 3 : 3;
          std::size_t from = i;
          while (from > 0 && from + back > i) --from;
          if (const auto tr = spatialPhraseIn(t, from)) {
            r = tr->relation;
            consumed.emplace_back(anchor.sentenceId, tr->begin, tr->end);
          }
        }
      }
      step.target.push_back(r);
    }
    if (step.target.empty() && s.objectAnchor.sentenceId >= 0) {
      // No target read: look for a spatial phrase after the object in its sentence.
      const std::vector<std::string> t = tokensOf(s.objectAnchor.sentenceId);
      if (const auto tr = spatialPhraseIn(t, static_cast<std::size_t>(std::max(0, s.objectAnchor.tokenId)))) {
        step.target.push_back(tr->relation);
        consumed.emplace_back(s.objectAnchor.sentenceId, tr->begin, tr->end);
        // "star right" of "the star right of the cuboid": the view word is not part of the name.
        const std::string name = srp::core::toLowerAscii(step.object.name);
        const auto space = name.rfind(' ');
        if (space != std::string::npos && isViewWord(name.substr(space + 1))) step.object.name = step.object.name.substr(0, space);
      }
    }
    objectSentence.push_back(s.objectAnchor.sentenceId);
    objectToken.push_back(s.objectAnchor.tokenId);
    out.steps.push_back(step);
  }
  ExecutionPlan kept;
  for (std::size_t i = 0; i < out.steps.size(); ++i) {
    const bool misread = out.steps[i].target.empty() && objectToken[i] >= 0 &&
                         std::any_of(consumed.begin(), consumed.end(), [&](const auto& c) {
                           return std::get<0>(c) == objectSentence[i] &&
                                  static_cast<std::size_t>(objectToken[i]) >= std::get<1>(c) &&
                                  static_cast<std::size_t>(objectToken[i]) < std::get<2>(c);
                         });
    if (!misread) kept.steps.push_back(out.steps[i]);
  }
  return kept;
}

}  // namespace srp::execution
