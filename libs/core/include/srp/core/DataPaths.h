#pragma once
/// \file DataPaths.h
/// \brief Where srp finds the data it ships: the knowledge base, the language
/// corpus and model, the scenes, the UR5 model, the default camera and the
/// bundled recordings.
///
/// The data folder has the layout of the source tree: `datasets/` (`kb/`,
/// `language/`, `real/`, ...), `sim/` (`scenes/`, `ur5/`, `cameras/`) and
/// `calib/`. It is looked up at run time, first match wins:
///  1. the folder given to DataPaths::setDataDir() (`srp --data-dir DIR`);
///  2. the environment variable `SRP_DATA_DIR`;
///  3. `<folder of the running executable>/../share/srp` (an installed srp:
///     `/usr/bin/srp` reads `/usr/share/srp`; a copied prefix moves with it);
///  4. the source tree of a build folder: CMake writes `srp-data-dir.txt` (one
///     line, the source folder) at the top of the build folder; it is found from
///     the executable's folder or one of its parents.
/// A folder named by 1 or 2 must exist: a typo is an error, never a fall-through
/// to another copy of the data. No path is compiled into the libraries.
///
/// \code
///   // what every default of srp goes through:
///   const std::filesystem::path kb = srp::core::DataPaths::file("datasets/kb/catalogue.json");
///   // a program that links srp and ships no data of its own:
///   srp::core::DataPaths::setDataDir("/usr/share/srp");
/// \endcode

#include <filesystem>
#include <optional>
#include <string>

namespace srp::core {

/// The run-time lookup of srp's data folder (see the file comment for the order).
class DataPaths {
 public:
  /// Which rule found the data folder.
  enum class Origin { Option, Environment, Install, BuildTree };

  /// The data folder and the rule that found it.
  struct Root {
    std::filesystem::path dir;
    Origin origin = Origin::Install;
  };

  /// Uses `dir` before every other rule from now on (`srp --data-dir`); an empty
  /// path clears it. Throws FileError naming `dir` when it is not a folder.
  static void setDataDir(const std::filesystem::path& dir);

  /// The data folder. Throws FileError listing the rules tried, and the fix
  /// (`--data-dir`, `SRP_DATA_DIR`), when none applies.
  static Root root();

  /// `root().dir / relative`. Throws FileError naming the data folder, the rule
  /// that chose it and the missing file when the file is not there.
  static std::filesystem::path file(const std::filesystem::path& relative);

  /// The data folder, or nothing when no rule applies (for help texts, which
  /// must not fail).
  static std::optional<Root> find();

  /// "--data-dir", "SRP_DATA_DIR", "next to the executable", "source tree of the build folder".
  static std::string describe(Origin origin);

  /// Name of the file CMake writes at the top of a build folder (rule 4).
  static constexpr const char* kBuildTreeMarker = "srp-data-dir.txt";
};

}  // namespace srp::core
