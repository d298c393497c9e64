#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "srp/core/Error.h"
#include "srp/core/Scene.h"

// Issue 21: seeded single-byte mutations and truncations of the default scene
// either load or fail with srp's own error naming the file; never another
// exception (a raw nlohmann message) or a crash.
TEST(SceneFuzz, MutatedScenesLoadOrNameTheFile) {
  constexpr int kCases = 1500;
  const std::string original = std::string(SRP_SIM_DIR) + "/scenes/default.json";
  std::ifstream in(original, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 100u);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("srp_scene_fuzz_" + std::to_string(::getpid()) + ".json")).string();
  std::mt19937 rng(21);
  int loaded = 0, refused = 0;
  for (int i = 0; i < kCases; ++i) {
    std::string m = bytes;
    if (i % 5 == 4) {
      m.resize(rng() % m.size());
    } else {
      const std::size_t at = rng() % m.size();
      m[at] = static_cast<char>(m[at] ^ static_cast<char>(1 + rng() % 255));
    }
    std::ofstream(path, std::ios::binary | std::ios::trunc) << m;
    try {
      srp::core::Scene::load(path);
      ++loaded;
    } catch (const srp::core::Error& e) {
      ++refused;
      const std::string what = e.what();
      EXPECT_NE(what.find(path), std::string::npos) << "case " << i << ": " << what;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "case " << i << ": not an srp error: " << e.what();
    }
  }
  std::filesystem::remove(path);
  EXPECT_EQ(loaded + refused, kCases);
  EXPECT_GT(refused, kCases / 2);
}
