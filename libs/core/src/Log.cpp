#include "srp/core/Log.h"

#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <optional>

#include "srp/core/Error.h"

namespace srp::core {
namespace {

/// Each Log::Level (in its order) with its name in --log-level and its spdlog level.
struct LevelEntry {
  const char* name;
  spdlog::level::level_enum spdlog;
};
constexpr LevelEntry kLevels[] = {{"trace", spdlog::level::trace}, {"debug", spdlog::level::debug},
                                  {"info", spdlog::level::info},   {"warning", spdlog::level::warn},
                                  {"error", spdlog::level::err},   {"off", spdlog::level::off}};

const LevelEntry& entryOf(Log::Level level) { return kLevels[static_cast<int>(level)]; }

std::optional<Log::Level> parseLevel(const std::string& name) {
  for (int k = 0; k < 6; ++k)
    if (name == kLevels[k].name) return static_cast<Log::Level>(k);
  if (name == "warn") return Log::Level::Warning;
  return std::nullopt;
}

/// The loggers (one per category, on one shared stderr sink) and the levels of SPEC.
class Registry {
 public:
  static Registry& get() {
    static Registry r;
    return r;
  }

  Log::Level level(std::string_view category) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = levels_.find(std::string(category));
    return it != levels_.end() ? it->second : defaultLevel_;
  }

  void write(std::string_view category, Log::Level level, const std::string& message) {
    std::shared_ptr<spdlog::logger> logger;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto& slot = loggers_[std::string(category)];
      if (!slot) {
        slot = std::make_shared<spdlog::logger>(std::string(category), sink_);
        slot->set_level(spdlog::level::trace);  // the level check is enabled()'s
        slot->set_pattern("%n: %l: %v");
      }
      logger = slot;
    }
    logger->log(entryOf(level).spdlog, message);
    logger->flush();
  }

  void set(const std::string& category, Log::Level level) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (category.empty()) {
      defaultLevel_ = level;
      levels_.clear();
    } else {
      levels_[category] = level;
    }
  }

 private:
  Registry() : sink_(std::make_shared<spdlog::sinks::stderr_sink_mt>()) { readLegacyEnvironment(); }

  /// The environment switches of earlier releases still turn their category on, with a note.
  void readLegacyEnvironment() {
    const std::pair<const char*, const char*> legacy[] = {
        {"SRP_PERCEPTION_DEBUG", "perception"}, {"SRP_DISCOVERY_DEBUG", "discovery"}, {"SRP_HAND_TRACE", "hand"}};
    for (const auto& [variable, category] : legacy)
      if (std::getenv(variable) != nullptr) {
        levels_[category] = Log::Level::Debug;
        std::fprintf(stderr, "srp: warning: %s is deprecated; use --log-level %s=debug\n", variable, category);
      }
  }

  std::mutex mutex_;
  std::shared_ptr<spdlog::sinks::stderr_sink_mt> sink_;
  std::map<std::string, std::shared_ptr<spdlog::logger>> loggers_;
  std::map<std::string, Log::Level> levels_;
  Log::Level defaultLevel_ = Log::Level::Info;
};

}  // namespace

bool Log::enabled(std::string_view category, Level level) {
  return level != Level::Off && level >= Registry::get().level(category);
}

void Log::write(std::string_view category, Level level, const std::string& message) {
  if (!enabled(category, level)) return;
  std::string line = message;
  while (!line.empty() && line.back() == '\n') line.pop_back();
  Registry::get().write(category, level, line);
}

void Log::writef(std::string_view category, Level level, const char* format, ...) {
  if (!enabled(category, level)) return;
  va_list args;
  va_start(args, format);
  va_list copy;
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, format, copy);
  va_end(copy);
  std::string text(n > 0 ? static_cast<std::size_t>(n) : 0, '\0');
  if (n > 0) std::vsnprintf(text.data(), text.size() + 1, format, args);
  va_end(args);
  write(category, level, text);
}

std::string Log::levelName(Level level) { return entryOf(level).name; }

void Log::setLevels(const std::string& spec) {
  std::string levels;
  for (const auto& l : kLevels) levels += (levels.empty() ? "" : ", ") + std::string(l.name);
  std::string names;
  for (const auto& [c, what] : categories()) names += (names.empty() ? "" : ", ") + c;
  std::size_t start = 0;
  while (start <= spec.size()) {
    const std::size_t comma = std::min(spec.find(',', start), spec.size());
    const std::string part = spec.substr(start, comma - start);
    start = comma + 1;
    if (part.empty()) continue;
    const std::size_t eq = part.find('=');
    const std::string category = eq == std::string::npos ? "" : part.substr(0, eq);
    const auto level = parseLevel(eq == std::string::npos ? part : part.substr(eq + 1));
    if (!level)
      throw InvalidInputError("log level '" + part + "': not a level; use one of " + levels +
                              ", or CATEGORY=LEVEL with a category of " + names);
    if (eq != std::string::npos &&
        std::none_of(categories().begin(), categories().end(), [&](const auto& c) { return c.first == category; }))
      throw InvalidInputError("log level '" + part + "': no category '" + category + "'; the categories are " + names);
    Registry::get().set(category, *level);
  }
}

const std::vector<std::pair<std::string, std::string>>& Log::categories() {
  static const std::vector<std::pair<std::string, std::string>> kCategories = {
      {"srp", "the commands themselves (deprecated spellings, notes)"},
      {"perception", "object detection, tracking and the edge yaw refinement, per frame and segment"},
      {"discovery", "parts and containers found without a CAD file (tables, rests, tracks)"},
      {"hand", "the marker-free hand detector (skin model, components, forearm, reach)"},
  };
  return kCategories;
}

}  // namespace srp::core
