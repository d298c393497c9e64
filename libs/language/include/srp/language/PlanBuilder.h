#pragma once
/// \file PlanBuilder.h
/// \brief Domain objects and plan steps from annotated sentences (the syntactic
/// half of the thesis' hybrid parser).
///
/// Each Action (recognised entity, or a manipulation verb the model missed)
/// opens a clause that runs to the next action. In a clause:
/// - the noun phrase(s) right after the verb are its target objects: a list
///   joined by "and"/"," gives one object each ("the cuboid and the cylinder");
///   multi-word names are kept ("aluminum workpiece", "item A", "Location 2");
///   Color entities (or WordNet colour words) inside the phrase give the colour;
/// - "it", "them", "they", "that", "the same" refer to the object(s) of the
///   latest clause that had objects (earlier sentences included);
/// - each indicator (SpatialIndicator/GoalIndicator entity, or a known
///   preposition such as "next to", "alongside") and the noun phrase after it
///   (its landmark) is a source location ("from", "off", "out of"; spatial
///   indicators of pick-like verbs, or before a later goal in the clause) or
///   else a target location, in the order written;
/// - an object without an open step gets a new step, so "place the octagon next
///   to the parallelogram" is a step without a pick clause (implicit pick);
///   a clause without objects ("and place in the box") applies to the latest ones;
/// - "back to"/"back in" marks the step a return: missing source/target are
///   taken from the reversed known move (this plan's earlier steps or `knownSteps`);
/// - text without any action that names objects of `knownSteps` ("only the star
///   this time") gives those known steps, in the order named.

#include <string>
#include <vector>

#include "srp/language/TaskPlan.h"
#include "srp/language/WordNetLexicon.h"

namespace srp::language {

/// Builds the ordered steps from `sentences` (tokens as written, entities and
/// relations as annotated). `knownSteps` are the steps of an earlier plan (for
/// "back to"); notes on anything skipped are appended to `warnings`.
std::vector<PlanStep> buildPlanSteps(const std::vector<AnnotatedSentence>& sentences, const WordNetLexicon& lexicon,
                                     const std::vector<PlanStep>& knownSteps, std::vector<std::string>& warnings);

}  // namespace srp::language
