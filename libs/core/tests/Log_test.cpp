#include "srp/core/Log.h"

#include <gtest/gtest.h>

#include "srp/core/Error.h"

namespace srp::core {
namespace {

// The levels are process-wide: each test sets what it needs and restores the default.
class LogLevels : public ::testing::Test {
 protected:
  void TearDown() override { Log::setLevels("info"); }
};

TEST_F(LogLevels, DefaultWritesInfoButNotDebug) {
  Log::setLevels("info");
  EXPECT_TRUE(Log::enabled("hand", Log::Level::Info));
  EXPECT_TRUE(Log::enabled("hand", Log::Level::Warning));
  EXPECT_FALSE(Log::enabled("hand", Log::Level::Debug));
}

TEST_F(LogLevels, CategoryLevelOverridesThePlainLevel) {
  Log::setLevels("warning,hand=debug");
  EXPECT_TRUE(Log::enabled("hand", Log::Level::Debug));
  EXPECT_FALSE(Log::enabled("hand", Log::Level::Trace));
  EXPECT_FALSE(Log::enabled("perception", Log::Level::Info));
  EXPECT_TRUE(Log::enabled("perception", Log::Level::Warning));
}

TEST_F(LogLevels, APlainLevelResetsTheCategories) {
  Log::setLevels("hand=trace");
  Log::setLevels("error");
  EXPECT_FALSE(Log::enabled("hand", Log::Level::Warning));
  EXPECT_TRUE(Log::enabled("hand", Log::Level::Error));
}

TEST_F(LogLevels, OffWritesNothing) {
  Log::setLevels("off");
  EXPECT_FALSE(Log::enabled("srp", Log::Level::Error));
}

TEST_F(LogLevels, WritesTheFormattedLineOnStderr) {
  Log::setLevels("perception=debug");
  ::testing::internal::CaptureStderr();
  Log::writef("perception", Log::Level::Debug, "frame %d: %.2f", 7, 0.5);
  Log::writef("perception", Log::Level::Trace, "not written");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "perception: debug: frame 7: 0.50\n");
}

TEST_F(LogLevels, BadSpecsNameThePartAndTheChoices) {
  try {
    Log::setLevels("hand=loud");
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("'hand=loud': not a level; use one of trace, debug"), std::string::npos)
        << e.what();
  }
  try {
    Log::setLevels("elbow=debug");
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("no category 'elbow'; the categories are srp, perception"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace srp::core
