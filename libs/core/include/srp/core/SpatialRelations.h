#pragma once

#include <string>

namespace srp::core {

/// True for the relation words of an instruction that mean "beside a landmark"
/// (next to, beside, adjacent to, near, alongside, by, close to, ...). One list
/// for the whole stack: the demo generator places and the executor plans with it.
bool isNeighbourRelation(const std::string& relation);

/// True for the relation words that mean "inside a container" (in, into,
/// inside, on, onto, to, back to, at, within).
bool isContainmentRelation(const std::string& relation);

}  // namespace srp::core
