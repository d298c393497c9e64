#pragma once
/// \file Log.h
/// \brief The diagnostics of srp: one named category per subsystem, a level
/// per category, written to stderr as `<category>: <level>: <message>`
/// (spdlog behind this interface; no spdlog type in it).
///
/// The `srp` commands set the levels from `-q` (warning), `-v` (debug) and
/// `--log-level SPEC`; SPEC is a level (`trace`, `debug`, `info`, `warning`,
/// `error`, `off`) and/or `category=level` pairs, comma-separated:
/// \code
///   srp perceive --demo d.rawlog --log-level hand=debug        # the marker-free hand's trace only
///   srp perceive --demo d.rawlog --log-level debug             # every category's trace
/// \endcode
/// The categories in use are listed by Log::categories(). In code:
/// \code
///   if (core::Log::enabled("hand", core::Log::Level::Debug))
///     core::Log::writef("hand", core::Log::Level::Debug, "frame %d: %d px", index, area);
/// \endcode
/// The level of a category not named in SPEC is SPEC's plain level (default: info).

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace srp::core {

class Log {
 public:
  enum class Level { Trace, Debug, Info, Warning, Error, Off };

  /// True when a message of `level` in `category` would be written (cheap: call it before formatting).
  static bool enabled(std::string_view category, Level level);
  /// Writes one line (no trailing newline needed) when enabled(category, level).
  static void write(std::string_view category, Level level, const std::string& message);
  /// printf-style write (the format is checked by the compiler).
  static void writef(std::string_view category, Level level, const char* format, ...)
      __attribute__((format(printf, 3, 4)));

  /// Applies a level SPEC (see the file comment). Throws InvalidInputError naming the bad part and the
  /// levels and categories it may use.
  static void setLevels(const std::string& spec);
  /// The level name as SPEC spells it ("warning" for Level::Warning).
  static std::string levelName(Level level);
  /// The categories srp's libraries write, with what each traces (for --help).
  static const std::vector<std::pair<std::string, std::string>>& categories();
};

}  // namespace srp::core
