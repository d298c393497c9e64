#include "srp/core/SafeText.h"

#include <gtest/gtest.h>

#include <map>
#include <random>

#include "srp/core/Error.h"

using srp::core::exportSafeText;
using srp::core::isSafeName;

namespace {

bool printableAscii(const std::string& s) {
  for (char c : s)
    if (c < 0x20 || c > 0x7E) return false;
  return true;
}

}  // namespace

// Every line break a controller or a YAML reader knows becomes an escape; the
// text around it stays readable.
TEST(SafeText, LineBreaksOfEveryKindAreEscaped) {
  EXPECT_EQ(exportSafeText("a\nb"), "a\\nb");
  EXPECT_EQ(exportSafeText("a\rb"), "a\\rb");
  EXPECT_EQ(exportSafeText("a\r\n---\nb"), "a\\r\\n---\\nb");
  EXPECT_EQ(exportSafeText("a\xC2\x85" "b"), "a\\u0085b");          // NEL
  EXPECT_EQ(exportSafeText("a\xE2\x80\xA8" "b"), "a\\u2028b");      // LINE SEPARATOR
  EXPECT_EQ(exportSafeText("a\xE2\x80\xA9" "b"), "a\\u2029b");      // PARAGRAPH SEPARATOR
  EXPECT_EQ(exportSafeText("a\x0B\x0C" "b"), "a\\u000B\\u000Cb");   // vertical tab, form feed
  EXPECT_EQ(exportSafeText("\xE2\x80\xAE" "evil"), "\\u202Eevil");  // RIGHT-TO-LEFT OVERRIDE
  EXPECT_EQ(exportSafeText("W\xC3\xBCrfel"), "W\\u00FCrfel");
  EXPECT_EQ(exportSafeText("\xF0\x9F\xA4\x96"), "\\U0001F916");
  EXPECT_EQ(exportSafeText("bad \xFF\xC3"), "bad \\xFF\\xC3");       // not UTF-8
  EXPECT_EQ(exportSafeText("\xED\xA0\x80"), "\\xED\\xA0\\x80");     // a UTF-16 surrogate is not UTF-8
  EXPECT_EQ(exportSafeText("\xC0\xAF"), "\\xC0\\xAF");              // overlong '/'
  // A backslash is doubled: "\\n" typed by a user cannot pose as one of our escapes.
  EXPECT_EQ(exportSafeText("C:\\new"), "C:\\\\new");
  EXPECT_EQ(exportSafeText(std::string("nul\0byte", 8)), "nul\\u0000byte");
  EXPECT_EQ(exportSafeText("Pick up the cuboid # and 'quotes' \"too\""), "Pick up the cuboid # and 'quotes' \"too\"");
}

TEST(SafeText, LongTextIsCutAtACharacterBoundary) {
  constexpr std::size_t kLimit = 20;
  EXPECT_EQ(exportSafeText(std::string(kLimit, 'a'), kLimit), std::string(kLimit, 'a'));
  EXPECT_EQ(exportSafeText(std::string(kLimit + 1, 'a'), kLimit), std::string(kLimit - 3, 'a') + "...");
  // Escapes are never cut in half.
  const std::string cut = exportSafeText(std::string(30, '\n'), kLimit);
  EXPECT_LE(cut.size(), kLimit);
  EXPECT_EQ(cut, "\\n\\n\\n\\n\\n\\n\\n\\n...");
  EXPECT_EQ(exportSafeText(std::string(100000, 'x')).size(), srp::core::kMaxExportTextLength);
}

// Random bytes and random code points: the output is printable ASCII, bounded,
// and two different inputs never give the same output below the length limit.
TEST(SafeText, RandomInputIsAlwaysPrintableAsciiAndUnambiguous) {
  constexpr int kCases = 20000;
  std::mt19937 rng(35);
  std::map<std::string, std::string> seen;
  for (int i = 0; i < kCases; ++i) {
    std::string in;
    const int length = static_cast<int>(rng() % 24);
    for (int k = 0; k < length; ++k) in += static_cast<char>(rng() % 256);
    const std::string out = exportSafeText(in);
    ASSERT_TRUE(printableAscii(out)) << i;
    ASSERT_LE(out.size(), srp::core::kMaxExportTextLength);
    const auto [it, inserted] = seen.emplace(out, in);
    if (!inserted) EXPECT_EQ(it->second, in) << "two inputs give '" << out << "'";
  }
}

TEST(SafeText, NamesUseASmallCharacterSet) {
  for (const char* good : {"blue box", "cuboid_red", "thesis-1", "v1.2", "A", "demo-seed-12"}) EXPECT_TRUE(isSafeName(good)) << good;
  for (const char* bad : {"", " lead", "trail ", "-dash", ".hidden", "a/b", "a\nb", "a\rb", "quote'", "semi;colon",
                          "tab\t", "hash#", "W\xC3\xBCrfel", "a\xE2\x80\xA8" "b", "new\x85line"})
    EXPECT_FALSE(isSafeName(bad)) << bad;
  EXPECT_FALSE(isSafeName(std::string(srp::core::kMaxNameLength + 1, 'a')));
  EXPECT_TRUE(isSafeName(std::string(srp::core::kMaxNameLength, 'a')));
  try {
    srp::core::requireSafeName("x\r\n---", "--name");
    FAIL() << "accepted";
  } catch (const srp::core::InvalidInputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--name"), std::string::npos) << what;
    EXPECT_NE(what.find("x\\r\\n---"), std::string::npos) << "the name is shown escaped: " << what;
    EXPECT_TRUE(printableAscii(what)) << what;
  }
}

TEST(SafeText, FileNamesStayInTheirFolder) {
  EXPECT_EQ(srp::core::safeFileName("blue box"), "blue_box");
  EXPECT_EQ(srp::core::safeFileName("../../etc/passwd"), "_._.._etc_passwd");
  EXPECT_EQ(srp::core::safeFileName(".."), "_.");
  EXPECT_EQ(srp::core::safeFileName(""), "_");
  EXPECT_EQ(srp::core::safeFileName("a\nb"), "a_b");
}
