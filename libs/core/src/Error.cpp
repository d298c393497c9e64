#include "srp/core/Error.h"

namespace srp::core {

FileError::FileError(const std::string& path, const std::string& problem)
    : Error("'" + path + "': " + problem), path_(path) {}

void require(bool condition, const std::string& message) {
  if (!condition) throw InvalidInputError(message);
}

}  // namespace srp::core
