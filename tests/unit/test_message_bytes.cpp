// Messages that quote a file's bytes: bytes that are not valid UTF-8, and control characters,
// reach the terminal (and Python) as \xNN, so an error line is always readable text.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "brdfcl/error.hpp"
#include "process.hpp"

using brdfcl::escapeMessage;
using brdfcl::test::RunResult;
using brdfcl::test::ScratchDir;

namespace {

// True when every byte of `s` belongs to valid UTF-8 and none is a control character but newline.
bool readableText(const std::string& s) { return escapeMessage(s) == s && s.find('\t') == std::string::npos; }

RunResult eval(const ScratchDir& dir, const std::string& materials, const std::string& samples) {
  brdfcl::test::writeFile(dir.path("m.json"), materials);
  brdfcl::test::writeFile(dir.path("s.csv"), samples);
  return brdfcl::test::runProcess({BRDFCL_CLI_PATH, "eval", "--materials", dir.path("m.json"), "--samples",
                                   dir.path("s.csv"), "--out", dir.path("o.csv")},
                                  dir.dir());
}

}  // namespace

TEST(MessageBytes, EscapesWhatIsNotText) {
  EXPECT_EQ(escapeMessage("plain text, unchanged"), "plain text, unchanged");
  EXPECT_EQ(escapeMessage("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80");
  EXPECT_EQ(escapeMessage("a\xfe" "b"), "a\\xFEb");
  EXPECT_EQ(escapeMessage("\x01\x7f"), "\\x01\\x7F");
  EXPECT_EQ(escapeMessage("line\nlog\ttab"), "line\nlog\ttab");  // build logs keep their lines
  EXPECT_EQ(escapeMessage("\xc0\xaf"), "\\xC0\\xAF");              // overlong '/'
  EXPECT_EQ(escapeMessage("\xed\xa0\x80"), "\\xED\\xA0\\x80");      // a surrogate
  EXPECT_EQ(escapeMessage("\xf4\x90\x80\x80"), "\\xF4\\x90\\x80\\x80");  // above U+10FFFF
  EXPECT_EQ(escapeMessage("cut \xe2\x82"), "cut \\xE2\\x82");       // a sequence cut short
  EXPECT_EQ(brdfcl::Error("got '\xfe'").what(), std::string("got '\\xFE'"));
}

TEST(MessageBytes, JsonParseErrorQuotesNoRawByte) {
  ScratchDir dir("msg-bytes-json");
  const RunResult r = eval(dir, "{\"materials\":[{\"name\":\"\xfe\x01", "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n");
  ASSERT_EQ(r.status, 2) << r.describe();
  EXPECT_TRUE(readableText(r.err)) << r.err;
  EXPECT_NE(r.err.find("\\xFE"), std::string::npos) << r.err;
}

TEST(MessageBytes, CsvFieldErrorQuotesNoRawByte) {
  ScratchDir dir("msg-bytes-csv");
  const RunResult r = eval(dir, "{\"materials\":[{}]}", "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,\xfe\x01\n");
  ASSERT_EQ(r.status, 2) << r.describe();
  EXPECT_TRUE(readableText(r.err)) << r.err;
  EXPECT_NE(r.err.find("'Vz'"), std::string::npos) << r.err;
}
