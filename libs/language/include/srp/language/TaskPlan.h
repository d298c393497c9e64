#pragma once
/// \file TaskPlan.h
/// \brief The Language Module's output: an ordered pick & place plan read from
/// one instruction, plus the per-sentence entity/relation annotation it came from.
///
/// This is the contract other modules (synthetic demos, programming, execution)
/// consume; its JSON form (toJson/taskPlanFromJson) is stable:
/// \code{.json}
/// {"steps": [{"object": {"name": "cuboid", "color": null},  // + "ordinal", "superlative", "relations" when given
///             "source": [{"relation": "from", "landmark": {"name": "box", "color": "blue"}}],
///             "target": [{"relation": "in",   "landmark": {"name": "box", "color": "gray"}}]}],
///  "sentences": [{"tokens": [...], "entities": [...], "relations": [...]}],
///  "warnings": []}
/// \endcode
/// `steps` are in execution order, one per target object; `source`/`target` are
/// empty when the instruction does not say. `sentences` use the corpus' SpERT
/// format (token indices, `end` exclusive). No geometry here: landmarks are names.

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace srp::language {

struct LocationRef;

/// A physical object named in the instruction: its name (multi-word names kept,
/// e.g. "aluminum workpiece", "item A", "Location 2"; common nouns lower-cased),
/// its colour adjective when one is given ("blue"), and the modifiers that pick
/// one of several such objects (resolved by execution::SceneGrounder):
/// - `ordinal`: "the second cube" -> 2, "the first" -> 1, "the last" -> -1;
/// - `superlative`: "the leftmost star" -> "leftmost" (also rightmost, frontmost,
///   backmost, biggest, smallest, highest, lowest, closest, farthest);
/// - `relations`: where the object is now, said inside its noun phrase: "the cube
///   that is behind the star" -> {"behind", star}; "the cube closest to the box"
///   -> {"closest to", box} (a superlative relative to a landmark).
struct ObjectRef {
  std::string name;
  std::optional<std::string> colour;
  std::optional<int> ordinal;
  std::string superlative;
  std::vector<LocationRef> relations;
  /// "[ordinal ][superlative ][color ]name[ relation landmark...]", e.g. "second red cube".
  std::string describe() const;
  bool operator==(const ObjectRef& o) const;
  bool operator!=(const ObjectRef& o) const { return !(*this == o); }
};

/// A location relative to a landmark object: `relation` is the indicator phrase
/// as written, lower-cased ("from", "in", "next to", "on top of"), `landmark`
/// the object after it.
/// `secondLandmark` and `corner` are filled by execution::planFromLanguage, which
/// re-reads those phrases from the tokens (the parser reads them only partly):
/// "between A and B" -> landmark A, secondLandmark B; "in the front left corner
/// of X" -> corner "front left" (view words, srp/core/ViewFrame.h). Not in the JSON form.
struct LocationRef {
  std::string relation;
  ObjectRef landmark;
  std::optional<ObjectRef> secondLandmark;
  std::string corner;
  bool operator==(const LocationRef& o) const {
    return relation == o.relation && landmark == o.landmark && secondLandmark == o.secondLandmark &&
           corner == o.corner;
  }
};

inline bool ObjectRef::operator==(const ObjectRef& o) const {
  return name == o.name && colour == o.colour && ordinal == o.ordinal && superlative == o.superlative &&
         relations == o.relations;
}

/// Where a plan element came from in the text (0-based sentence and token index).
struct TokenAnchor {
  int sentenceId = -1;
  int tokenId = -1;
};

/// One pick & place step: move `object` from `source` (all locations that
/// describe where it is now, most specific first) to `target` (all that describe
/// where it goes, most specific first, e.g. "next to the cuboid", "in the gray box").
struct PlanStep {
  ObjectRef object;
  std::vector<LocationRef> source, target;
  /// "back to ...": the step returns the object where a known move took it from.
  bool isReturn = false;
  /// First mention of the object and of each landmark (same order as source/target).
  TokenAnchor objectAnchor;
  std::vector<TokenAnchor> sourceAnchors, targetAnchors;
};

/// A SpERT entity: tokens [start, end) of one sentence, `type` one of Action,
/// Trajector, SpatialIndicator, GoalIndicator, Color.
struct EntitySpan {
  int start = 0, end = 0;
  std::string type;
  bool operator==(const EntitySpan& o) const { return start == o.start && end == o.end && type == o.type; }
};

/// A SpERT relation: `type` Spatial (Trajector -> SpatialIndicator) or
/// Transition (Action -> GoalIndicator); head/tail index `entities`.
struct RelationLink {
  int head = 0, tail = 0;
  std::string type;
};

/// One tokenised sentence with its entities and relations (the corpus format).
/// `charBegin/charEnd` give each token's byte offsets in the parsed text (empty
/// for corpus sentences).
struct AnnotatedSentence {
  std::vector<std::string> tokens;
  std::vector<EntitySpan> entities;
  std::vector<RelationLink> relations;
  std::vector<int> charBegin, charEnd;
};

/// The plan of one instruction. Zero steps with a warning saying why when the
/// text is not a usable instruction (empty, too long, no action, not English).
struct TaskPlan {
  std::vector<PlanStep> steps;
  std::vector<AnnotatedSentence> sentences;
  std::vector<std::string> warnings;
};

nlohmann::json toJson(const ObjectRef& o);
nlohmann::json toJson(const LocationRef& l);
nlohmann::json toJson(const PlanStep& s);
nlohmann::json toJson(const AnnotatedSentence& s);
/// {"steps": [...], "sentences": [...], "warnings": [...]} as documented above.
nlohmann::json toJson(const TaskPlan& plan);

ObjectRef objectRefFromJson(const nlohmann::json& j);
/// Reads the SpERT form; throws srp::core::InvalidInputError naming the bad field.
AnnotatedSentence annotatedSentenceFromJson(const nlohmann::json& j);
/// Inverse of toJson(TaskPlan) (anchors are not stored); throws InvalidInputError.
TaskPlan taskPlanFromJson(const nlohmann::json& j);

/// "the blue box" style text for people: "[color ]name" (ObjectRef::describe, with modifiers).
std::string describe(const ObjectRef& o);
/// A readable multi-line rendering of the plan (steps, then warnings).
std::string describe(const TaskPlan& plan);

}  // namespace srp::language
