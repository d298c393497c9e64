#pragma once
/// \file SkillType.h
/// \brief The four skills a pick & place step is segmented into (thesis ch. 6.4).

#include <array>
#include <string>

namespace srp::core {

enum class SkillType { Reach, Grasp, Move, Release };

inline constexpr std::array<SkillType, 4> kAllSkillTypes = {SkillType::Reach, SkillType::Grasp,
                                                            SkillType::Move, SkillType::Release};

/// "Reach", "Grasp", "Move" or "Release".
std::string toString(SkillType s);

/// Inverse of toString (case-sensitive); throws InvalidInputError naming the text.
SkillType skillTypeFromString(const std::string& text);

}  // namespace srp::core
