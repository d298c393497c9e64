#pragma once
/// \file Error.h
/// \brief The error types of srp. Apps turn them into a one-line message and a
/// non-zero exit; the message names the bad input and, where there is one, the fix.

#include <stdexcept>
#include <string>

namespace srp::core {

/// Base class of every error srp throws on purpose.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// The caller gave input that cannot be used (a bad file, a missing field, a
/// NaN sample). The message names the input and says how to fix it.
class InvalidInputError : public Error {
 public:
  using Error::Error;
};

/// A file could not be read or written (missing, unreadable, corrupt, or of a
/// newer format version than this build knows).
class FileError : public Error {
 public:
  FileError(const std::string& path, const std::string& problem);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// Throws InvalidInputError(message) when condition is false.
void require(bool condition, const std::string& message);

}  // namespace srp::core
