#include "srp/language/TaskPlan.h"

#include <sstream>

#include "srp/core/Error.h"
#include "srp/core/Json.h"

namespace srp::language {

using nlohmann::json;

json toJson(const ObjectRef& o) {
  json j{{"name", o.name}, {"color", o.colour ? json(*o.colour) : json(nullptr)}};
  // Modifiers only when given: plans without them keep their JSON form.
  if (o.ordinal) j["ordinal"] = *o.ordinal;
  if (!o.superlative.empty()) j["superlative"] = o.superlative;
  if (!o.relations.empty()) {
    j["relations"] = json::array();
    for (const auto& r : o.relations) j["relations"].push_back(toJson(r));
  }
  return j;
}

std::string ObjectRef::describe() const {
  static const char* kOrdinals[] = {"", "first", "second", "third", "fourth", "fifth",
                                    "sixth", "seventh", "eighth", "ninth", "tenth"};
  std::string s;
  if (ordinal) s += *ordinal == -1 ? std::string("last ")
                    : (*ordinal >= 1 && *ordinal <= 10) ? std::string(kOrdinals[*ordinal]) + " "
                                                        : "#" + std::to_string(*ordinal) + " ";
  if (!superlative.empty()) s += superlative + " ";
  if (colour) s += *colour + " ";
  s += name;
  for (const auto& r : relations) s += " " + r.relation + " the " + r.landmark.describe();
  return s;
}

json toJson(const LocationRef& l) { return json{{"relation", l.relation}, {"landmark", toJson(l.landmark)}}; }

json toJson(const PlanStep& s) {
  json src = json::array(), dst = json::array();
  for (const auto& l : s.source) src.push_back(toJson(l));
  for (const auto& l : s.target) dst.push_back(toJson(l));
  return json{{"object", toJson(s.object)}, {"source", src}, {"target", dst}};
}

json toJson(const AnnotatedSentence& s) {
  json ents = json::array(), rels = json::array();
  for (const auto& e : s.entities) ents.push_back({{"start", e.start}, {"end", e.end}, {"type", e.type}});
  for (const auto& r : s.relations) rels.push_back({{"head", r.head}, {"tail", r.tail}, {"type", r.type}});
  return json{{"tokens", s.tokens}, {"entities", ents}, {"relations", rels}};
}

json toJson(const TaskPlan& plan) {
  json steps = json::array(), sentences = json::array();
  for (const auto& s : plan.steps) steps.push_back(toJson(s));
  for (const auto& s : plan.sentences) sentences.push_back(toJson(s));
  return json{{"steps", steps}, {"sentences", sentences}, {"warnings", plan.warnings}};
}

ObjectRef objectRefFromJson(const json& j) {
  ObjectRef o;
  o.name = core::requireField(j, "name", "object").get<std::string>();
  if (j.contains("color") && !j.at("color").is_null()) o.colour = j.at("color").get<std::string>();
  if (j.contains("ordinal") && !j.at("ordinal").is_null()) o.ordinal = j.at("ordinal").get<int>();
  o.superlative = j.value("superlative", std::string());
  if (j.contains("relations"))
    for (const auto& l : j.at("relations"))
      o.relations.push_back({core::requireField(l, "relation", "object relations").get<std::string>(),
                             objectRefFromJson(core::requireField(l, "landmark", "object relations")), std::nullopt, {}});
  return o;
}

static std::vector<LocationRef> locationsFromJson(const json& j, const std::string& key) {
  std::vector<LocationRef> out;
  if (!j.contains(key)) return out;
  for (const auto& l : j.at(key))
    out.push_back({core::requireField(l, "relation", key).get<std::string>(),
                   objectRefFromJson(core::requireField(l, "landmark", key)), std::nullopt, {}});
  return out;
}

// The published corpus writes a few indices as strings ("4"); accept both.
static int indexFromJson(const json& v) { return v.is_string() ? std::stoi(v.get<std::string>()) : v.get<int>(); }

AnnotatedSentence annotatedSentenceFromJson(const json& j) {
  AnnotatedSentence s;
  try {
    s.tokens = core::requireField(j, "tokens", "sentence").get<std::vector<std::string>>();
    const int n = static_cast<int>(s.tokens.size());
    for (const auto& e : core::requireField(j, "entities", "sentence")) {
      EntitySpan span{indexFromJson(e.at("start")), indexFromJson(e.at("end")), e.at("type").get<std::string>()};
      core::require(span.start >= 0 && span.start < span.end && span.end <= n,
                    "sentence entity [" + std::to_string(span.start) + ", " + std::to_string(span.end) +
                        ") lies outside the " + std::to_string(n) + " tokens; fix the corpus entry");
      s.entities.push_back(span);
    }
    if (j.contains("relations"))
      for (const auto& r : j.at("relations")) {
        RelationLink link{indexFromJson(r.at("head")), indexFromJson(r.at("tail")), r.at("type").get<std::string>()};
        const int m = static_cast<int>(s.entities.size());
        core::require(link.head >= 0 && link.head < m && link.tail >= 0 && link.tail < m,
                      "sentence relation refers to a missing entity; fix the corpus entry");
        s.relations.push_back(link);
      }
  } catch (const std::logic_error& e) {  // json errors, std::stoi
    throw core::InvalidInputError(std::string("sentence is not in SpERT format (") + e.what() +
                                  "); expected {\"tokens\", \"entities\", \"relations\"}");
  }
  return s;
}

TaskPlan taskPlanFromJson(const json& j) {
  TaskPlan plan;
  try {
    for (const auto& s : core::requireField(j, "steps", "task plan")) {
      PlanStep step;
      step.object = objectRefFromJson(core::requireField(s, "object", "step"));
      step.source = locationsFromJson(s, "source");
      step.target = locationsFromJson(s, "target");
      plan.steps.push_back(step);
    }
    if (j.contains("sentences"))
      for (const auto& s : j.at("sentences")) plan.sentences.push_back(annotatedSentenceFromJson(s));
    if (j.contains("warnings")) plan.warnings = j.at("warnings").get<std::vector<std::string>>();
  } catch (const json::exception& e) {
    throw core::InvalidInputError(std::string("task plan JSON is malformed (") + e.what() +
                                  "); expected the format of srp parse --json");
  }
  return plan;
}

std::string describe(const ObjectRef& o) { return o.describe(); }

std::string describe(const TaskPlan& plan) {
  std::ostringstream out;
  out << plan.steps.size() << (plan.steps.size() == 1 ? " step" : " steps") << "\n";
  for (size_t i = 0; i < plan.steps.size(); ++i) {
    const auto& s = plan.steps[i];
    out << "  " << i + 1 << ". move the " << describe(s.object);
    for (const auto& l : s.source) out << " [" << l.relation << " the " << describe(l.landmark) << "]";
    out << " ->";
    if (s.target.empty()) out << " (target not given)";
    for (const auto& l : s.target) out << " [" << l.relation << " the " << describe(l.landmark) << "]";
    if (s.isReturn) out << " (back)";
    out << "\n";
  }
  for (const auto& w : plan.warnings) out << "warning: " << w << "\n";
  return out.str();
}

}  // namespace srp::language
