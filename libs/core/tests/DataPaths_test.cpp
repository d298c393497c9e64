#include "srp/core/DataPaths.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <functional>

#include "srp/core/DefaultScene.h"
#include "srp/core/Error.h"
#include "srp/core/ObjectCatalogue.h"

namespace fs = std::filesystem;
using srp::core::DataPaths;

namespace {

/// Each test starts with no --data-dir and no SRP_DATA_DIR, and restores them.
class DataPathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const char* env = std::getenv("SRP_DATA_DIR")) savedEnv_ = env;
    ::unsetenv("SRP_DATA_DIR");
    DataPaths::setDataDir({});
    dir_ = fs::temp_directory_path() / ("srp_datapaths_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "datasets" / "kb");
    std::ofstream(dir_ / "datasets" / "kb" / "catalogue.json") << "{}";
  }
  void TearDown() override {
    DataPaths::setDataDir({});
    if (savedEnv_.empty()) ::unsetenv("SRP_DATA_DIR");
    else ::setenv("SRP_DATA_DIR", savedEnv_.c_str(), 1);
    fs::remove_all(dir_);
  }
  fs::path dir_;
  std::string savedEnv_;
};

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const srp::core::FileError& e) {
    return e.what();
  }
  return "(no FileError)";
}

}  // namespace

// A test program of the build folder finds the source tree through srp-data-dir.txt,
// the same data the tests' compile-time paths name.
TEST_F(DataPathsTest, BuildFolderFindsTheSourceTree) {
  const DataPaths::Root r = DataPaths::root();
  EXPECT_EQ(r.origin, DataPaths::Origin::BuildTree);
  EXPECT_TRUE(fs::equivalent(r.dir, SRP_SOURCE_DIR)) << r.dir;
  EXPECT_TRUE(fs::equivalent(srp::core::ObjectCatalogue::defaultPath(), fs::path(SRP_DATASETS_DIR) / "kb/catalogue.json"));
  EXPECT_TRUE(fs::equivalent(srp::core::defaultScenePath(), fs::path(SRP_SIM_DIR) / "scenes/default.json"));
}

TEST_F(DataPathsTest, EnvironmentThenOptionWin) {
  ::setenv("SRP_DATA_DIR", dir_.c_str(), 1);
  EXPECT_EQ(DataPaths::root().origin, DataPaths::Origin::Environment);
  EXPECT_TRUE(fs::equivalent(DataPaths::file("datasets/kb/catalogue.json"), dir_ / "datasets/kb/catalogue.json"));

  const fs::path other = dir_ / "other";
  fs::create_directories(other);
  DataPaths::setDataDir(other);
  EXPECT_EQ(DataPaths::root().origin, DataPaths::Origin::Option);
  EXPECT_TRUE(fs::equivalent(DataPaths::root().dir, other));
  // The chosen folder lacks the file: the error names the file, the folder's rule and the fix.
  const std::string m = messageOf([] { DataPaths::file("datasets/kb/catalogue.json"); });
  EXPECT_NE(m.find("other/datasets/kb/catalogue.json"), std::string::npos) << m;
  EXPECT_NE(m.find("chosen by --data-dir"), std::string::npos) << m;
  EXPECT_NE(m.find("SRP_DATA_DIR"), std::string::npos) << m;
}

// A folder named by the user that is not there is an error, never a fall-through to
// another copy of the data.
TEST_F(DataPathsTest, MissingNamedFolderIsAnError) {
  const fs::path missing = dir_ / "no_such_folder";
  EXPECT_THROW(DataPaths::setDataDir(missing), srp::core::FileError);
  ::setenv("SRP_DATA_DIR", missing.c_str(), 1);
  EXPECT_FALSE(DataPaths::find().has_value());
  const std::string m = messageOf([] { DataPaths::root(); });
  EXPECT_NE(m.find("no_such_folder"), std::string::npos) << m;
  EXPECT_NE(m.find("SRP_DATA_DIR names no folder"), std::string::npos) << m;
  EXPECT_THROW(srp::core::ObjectCatalogue::defaultPath(), srp::core::FileError);
}
