#include "srp/core/SkillType.h"

#include "srp/core/Error.h"

namespace srp::core {

std::string toString(SkillType s) {
  switch (s) {
    case SkillType::Reach: return "Reach";
    case SkillType::Grasp: return "Grasp";
    case SkillType::Move: return "Move";
    case SkillType::Release: return "Release";
  }
  return "?";
}

SkillType skillTypeFromString(const std::string& text) {
  for (SkillType s : kAllSkillTypes)
    if (toString(s) == text) return s;
  throw InvalidInputError("unknown skill type '" + text +
                          "' (expected Reach, Grasp, Move or Release)");
}

}  // namespace srp::core
