#pragma once
/// \file LanguageSwitches.h
/// \brief The `--rules` / `--features` settings of the language commands
/// ("span_lengths=0,source_is_spatial=1") applied to DecodingRules / FeatureGroups.

#include <string>
#include <vector>

#include "srp/core/Error.h"

namespace srp::app {

/// The names of a switch set, separated by spaces (for --help and error messages).
template <typename Switches>
inline std::string switchNames() {
  std::string names;
  for (const auto& [n, member] : Switches::all()) names += (names.empty() ? "" : " ") + n;
  return names;
}

/// "name=0,name=1" settings of a switch set (DecodingRules / FeatureGroups).
template <typename Switches>
inline void applySwitches(const std::vector<std::string>& settings, Switches& s, const std::string& what) {
  for (const auto& setting : settings) {
    const auto eq = setting.find('=');
    const std::string name = setting.substr(0, eq);
    bool found = false;
    for (const auto& [n, member] : Switches::all())
      if (n == name) {
        s.*member = eq == std::string::npos || setting.substr(eq + 1) != "0";
        found = true;
      }
    if (!found)
      throw srp::core::InvalidInputError("unknown " + what + " '" + name + "'; one of: " + switchNames<Switches>());
  }
}

}  // namespace srp::app
