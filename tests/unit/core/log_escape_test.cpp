// core/log_escape.h: a string from a peer becomes one line of printable ASCII that says
// exactly which bytes came, bounded in length.
#include "core/log_escape.h"

#include <gtest/gtest.h>

#include <string>

using crashlink::core::log_escape;

TEST(LogEscape, PrintableAsciiIsKept) {
  EXPECT_EQ(log_escape("fine"), "fine");
  EXPECT_EQ(log_escape("car-2_left.v1 'x' (y)"), "car-2_left.v1 'x' (y)");
  EXPECT_EQ(log_escape(""), "");
}

TEST(LogEscape, NewlinesAndControlCharactersBecomeHex) {
  // The forged line of issue 20: a Hello whose domain carries a newline and a fake end of run.
  const std::string forged = "fine\ncrashlink-coordinator: done: all domains finished";
  const std::string out = log_escape(forged);
  EXPECT_EQ(out, "fine\\x0acrashlink-coordinator: done: all domains finished");
  EXPECT_EQ(out.find('\n'), std::string::npos);
  EXPECT_EQ(log_escape("a\rb\tc"), "a\\x0db\\x09c");
  EXPECT_EQ(log_escape(std::string("\0x", 2)), "\\x00x");
  EXPECT_EQ(log_escape("\x7f"), "\\x7f");
}

TEST(LogEscape, TerminalEscapesAndNonAsciiBecomeHex) {
  EXPECT_EQ(log_escape("\x1b[2J\x1b]0;pwned\x07"), "\\x1b[2J\\x1b]0;pwned\\x07");
  EXPECT_EQ(log_escape("Wischer/\xc3\xbc"), "Wischer/\\xc3\\xbc");  // UTF-8 'ü' too
  EXPECT_EQ(log_escape("\xff\xfe"), "\\xff\\xfe");
}

TEST(LogEscape, TheBackslashIsEscapedSoThatTheOutputIsUnambiguous) {
  // A peer sending the four characters \x0a must not look like one that sent a newline.
  EXPECT_EQ(log_escape("\\x0a"), "\\x5cx0a");
  EXPECT_NE(log_escape("\\x0a"), log_escape("\n"));
}

TEST(LogEscape, LengthIsBounded) {
  const std::string long_name(1000, 'a');
  const std::string out = log_escape(long_name);
  EXPECT_EQ(out, std::string(crashlink::core::kLogNameBytes, 'a') + "...(+872 bytes)");
  EXPECT_EQ(log_escape("abcdef", 3), "abc...(+3 bytes)");
  EXPECT_EQ(log_escape("abc", 3), "abc");
  // Every byte escaped: at most 4 characters per byte shown, plus the note.
  const std::string nl(10000, '\n');
  EXPECT_LE(log_escape(nl).size(), 4 * crashlink::core::kLogNameBytes + 20);
}
