#include "srp/core/OutputFile.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "srp/core/Error.h"

namespace fs = std::filesystem;
using srp::core::PathRole;

namespace {

class OutputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("srp_outputfile_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    srp::core::injectOutputWriteFailureAfter(-1);
    fs::remove_all(dir_);
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static void put(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }
  std::size_t entries() const { return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {})); }
  fs::path dir_;
};

TEST_F(OutputFileTest, WritesAndReplacesAtomically) {
  const fs::path f = dir_ / "a.txt";
  srp::core::writeFileAtomically(f, "first");
  EXPECT_EQ(read(f), "first");
  srp::core::writeFileAtomically(f, "second");
  EXPECT_EQ(read(f), "second");
  EXPECT_EQ(entries(), 1u);  // no temporary left
}

TEST_F(OutputFileTest, UncommittedLeavesTheTargetAsItWas) {
  const fs::path f = dir_ / "a.txt";
  put(f, "old");
  {
    srp::core::AtomicOutputFile out(f);
    out.write("new, never committed");
  }
  EXPECT_EQ(read(f), "old");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFileTest, FullDiskKeepsThePreviousFile) {
  const fs::path f = dir_ / "prog.script";
  put(f, "old program");
  srp::core::injectOutputWriteFailureAfter(10);
  EXPECT_THROW(srp::core::writeFileAtomically(f, std::string(1000, 'x')), srp::core::FileError);
  srp::core::injectOutputWriteFailureAfter(-1);
  EXPECT_EQ(read(f), "old program");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFileTest, FilesTogetherAreBothOrNeither) {
  const fs::path a = dir_ / "task.script", b = dir_ / "trajectory.yaml";
  put(a, "old script");
  put(b, "old yaml");
  // The second file's write fails: neither changes.
  srp::core::injectOutputWriteFailureAfter(15);
  EXPECT_THROW(srp::core::writeFilesTogether({{a, "new script"}, {b, "new yaml, long enough to fail"}}),
               srp::core::FileError);
  srp::core::injectOutputWriteFailureAfter(-1);
  EXPECT_EQ(read(a), "old script");
  EXPECT_EQ(read(b), "old yaml");
  // The second target cannot be renamed onto (it is a folder): the first is restored.
  const fs::path c = dir_ / "blocked";
  fs::create_directory(c);
  EXPECT_THROW(srp::core::writeFilesTogether({{a, "new script"}, {c, "x"}}), srp::core::FileError);
  EXPECT_EQ(read(a), "old script");
  srp::core::writeFilesTogether({{a, "new script"}, {b, "new yaml"}});
  EXPECT_EQ(read(a), "new script");
  EXPECT_EQ(read(b), "new yaml");
  EXPECT_EQ(entries(), 3u);  // a, b, the folder: no temporaries or backups
}

TEST_F(OutputFileTest, RefusesAnOutputThatIsAnInput) {
  const fs::path db = dir_ / "task.db";
  put(db, "db");
  // The same file by another name: relative, with "..", through a hard link and a symlink.
  fs::create_hard_link(db, dir_ / "hard.db");
  fs::create_symlink(db, dir_ / "soft.db");
  for (const fs::path& alias : {db, dir_ / "sub" / ".." / "task.db", dir_ / "hard.db", dir_ / "soft.db"}) {
    try {
      srp::core::checkOutputPaths({PathRole{"--urscript", alias}}, {PathRole{"--db", db}}, true);
      ADD_FAILURE() << alias << " was accepted as an output over the input";
    } catch (const srp::core::InvalidInputError& e) {
      EXPECT_NE(std::string(e.what()).find("--db"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("--urscript"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(read(db), "db");
}

TEST_F(OutputFileTest, RefusesAnOutputInsideAnInputFolderAndTwoOutputsOnOneFile) {
  fs::create_directory(dir_ / "frames");
  EXPECT_THROW(srp::core::checkOutputPaths({PathRole{"-o", dir_ / "frames" / "x.rawlog"}},
                                           {PathRole{"input folder", dir_ / "frames"}}, true),
               srp::core::InvalidInputError);
  EXPECT_THROW(srp::core::checkOutputPaths({PathRole{"--urscript", dir_ / "t.out"}, PathRole{"--trajectory-yaml", dir_ / "t.out"}},
                                           {}, true),
               srp::core::InvalidInputError);
  EXPECT_NO_THROW(srp::core::checkOutputPaths({PathRole{"-o", dir_ / "x.rawlog"}},
                                              {PathRole{"input folder", dir_ / "frames"}}, false));
}

TEST_F(OutputFileTest, ExistingOutputNeedsOverwrite) {
  const fs::path f = dir_ / "out.json";
  put(f, "{}");
  EXPECT_THROW(srp::core::checkOutputPaths({PathRole{"-o", f}}, {}, false), srp::core::InvalidInputError);
  EXPECT_NO_THROW(srp::core::checkOutputPaths({PathRole{"-o", f}}, {}, true));
}

TEST_F(OutputFileTest, FolderIsReplacedWholeOrNotAtAll) {
  const fs::path report = dir_ / "report";
  fs::create_directory(report);
  put(report / "stale.png", "old");
  {
    srp::core::AtomicOutputFolder out(report);
    put(out.temporaryPath() / "summary.md", "half");
  }  // not committed: the old folder stays, no temporary left
  EXPECT_TRUE(fs::exists(report / "stale.png"));
  EXPECT_EQ(entries(), 1u);
  {
    srp::core::AtomicOutputFolder out(report);
    put(out.temporaryPath() / "summary.md", "new");
    out.commit();
  }
  EXPECT_FALSE(fs::exists(report / "stale.png"));
  EXPECT_EQ(read(report / "summary.md"), "new");
  EXPECT_EQ(entries(), 1u);
}

}  // namespace
