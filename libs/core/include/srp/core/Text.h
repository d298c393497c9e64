#pragma once
/// \file Text.h
/// \brief Small text helpers shared by the modules.

#include <string>

namespace srp::core {

/// `text` with the ASCII letters A-Z lower-cased; every other byte (UTF-8
/// included) unchanged, independent of the C locale.
std::string toLowerAscii(std::string text);

/// A name as written in scenes, catalogues and instructions, made comparable:
/// lower-cased (toLowerAscii), '_' and '-' read as spaces, outer spaces trimmed
/// ("Blue_Box " -> "blue box").
std::string normaliseName(std::string name);

}  // namespace srp::core
