#pragma once
/// \file DefaultScene.h
/// \brief Where the bundled thesis scene is (the default of every command
/// and session that takes a scene), next to ObjectCatalogue::defaultPath().

#include <string>

namespace srp::core {

/// `sim/scenes/default.json` of srp's data folder (DataPaths); throws FileError
/// when it is not there.
std::string defaultScenePath();

}  // namespace srp::core
