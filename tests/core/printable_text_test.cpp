// Escaping for messages: control bytes and broken UTF-8 become \xNN, real UTF-8 text stays readable.
#include "io/printable_text.hpp"

#include <gtest/gtest.h>

namespace {

TEST(PrintableText, EscapesControlBytesAndBrokenUtf8) {
  EXPECT_EQ(pkm::printable_text(std::string("a\x1b[31m\x07\x00z", 9)), "a\\x1B[31m\\x07\\x00z");
  EXPECT_EQ(pkm::printable_text("\xff\xfe"), "\\xFF\\xFE");
  EXPECT_EQ(pkm::printable_text("\x7f"), "\\x7F");
  EXPECT_EQ(pkm::printable_text("\xC0\xAF"), "\\xC0\\xAF");  // overlong '/'
  EXPECT_EQ(pkm::printable_text("\xE2\x80"), "\\xE2\\x80");  // cut short
}

TEST(PrintableText, KeepsUtf8Text) {
  EXPECT_EQ(pkm::printable_text("≤ 200 %, ρ_max 1 µm, 5°"), "≤ 200 %, ρ_max 1 µm, 5°");
  EXPECT_EQ(pkm::printable_text("\xF0\x9F\x94\xA7"), "\xF0\x9F\x94\xA7");
  EXPECT_EQ(pkm::printable_text("plain\\text"), "plain\\text");
}

TEST(PrintableText, CutsLongTextBetweenCharacters) {
  // Built with append: GCC 12 warns (-Warray-bounds, falsely) on "literal" + std::string(n, c) when inlined.
  std::string line = "G1 X";
  line.append(5000, '7');
  std::string expected = "G1 X";
  expected.append(996, '7');
  expected += "… (4004 more bytes)";
  EXPECT_EQ(pkm::printable_text(line), expected);
  EXPECT_EQ(pkm::printable_text("ab\x01", 3), "ab\\x01");
}

}  // namespace
