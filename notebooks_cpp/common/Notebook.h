#pragma once
/// \file Notebook.h
/// \brief What every notebook does around its content: the output folder, the
/// checks that keep its page honest (a failed one makes the CTest fail), and a
/// main() that turns an exception into a one-line message and exit code 1.

#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>

namespace srp::notebook {

/// The folder given as the first argument, else out/notebooks/<topic>; created.
inline std::filesystem::path outputFolder(int argc, char** argv, const std::string& topic) {
  const std::filesystem::path out = argc > 1 ? std::filesystem::path(argv[1]) : std::filesystem::path("out/notebooks") / topic;
  std::filesystem::create_directories(out);
  return out;
}

/// The notebook's checks: each failed one is printed ("CHECK FAILED: ...") and
/// makes exitCode() 1.
class Checks {
 public:
  void require(bool condition, const std::string& what) {
    if (!condition) std::cerr << "CHECK FAILED: " << what << "\n";
    ok_ = ok_ && condition;
  }
  /// The figure exists and is more than an empty canvas (> 10 kB).
  void pngWritten(const std::filesystem::path& png) {
    require(std::filesystem::exists(png) && std::filesystem::file_size(png) > 10000, png.string() + " written");
  }
  int exitCode() const { return ok_ ? 0 : 1; }

 private:
  bool ok_ = true;
};

/// Runs a notebook's body; an exception becomes "notebook <topic>: <message>" and exit code 1.
inline int run(const std::string& topic, int argc, char** argv, const std::function<int(int, char**)>& body) {
  try {
    return body(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "notebook " << topic << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace srp::notebook
