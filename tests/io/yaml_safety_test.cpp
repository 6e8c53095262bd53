// What the one YAML reader (io/yaml_reader.hpp, io/yaml_stream_check.hpp) refuses before any reader walks
// the tree: alias cycles and alias bombs, a second document, an unclosed quote, a NUL byte; and the checks
// on labels, points and numbers that name the key instead of blaming what is computed from it.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "io/machine_file.hpp"
#include "io/yaml_reader.hpp"
#include "io/yaml_stream_check.hpp"

namespace pkm {
namespace {

std::string yaml_safety_error(const std::string& text) {
  auto parsed = parse_yaml_document(text, "f.yaml");
  return parsed ? std::string("(accepted)") : parsed.error().message;
}

// Nine anchors of nine aliases each: 9^9 nodes if walked.
std::string yaml_safety_bomb() {
  std::string text = "a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1]\n";
  for (int i = 1; i < 10; ++i) {
    text += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [";
    for (int k = 0; k < 9; ++k) text += (k ? ", *a" : "*a") + std::to_string(i - 1);
    text += "]\n";
  }
  return text;
}

TEST(YamlSafety, AnAliasInsideItsOwnNodeIsACycle) {
  EXPECT_EQ(yaml_safety_error("name: &r [*r]\n"),
            "f.yaml:1:11: alias *r: the alias is inside the node that &r names (1:7): an endless cycle");
  EXPECT_EQ(yaml_safety_error("type: x\ndefault: &r {tangential: *r}\n"),
            "f.yaml:2:26: alias *r: the alias is inside the node that &r names (2:10): an endless cycle");
  // Deeper down: the alias two levels inside.
  EXPECT_NE(yaml_safety_error("a: &top\n  b:\n    - [1, *top]\n").find("f.yaml:3:11: alias *top"),
            std::string::npos);
}

TEST(YamlSafety, AnAliasBombIsRefusedQuickly) {
  const auto start = std::chrono::steady_clock::now();
  const std::string error = yaml_safety_error(yaml_safety_bomb());
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NE(error.find("aliases expand the file to more than 100000 nodes"), std::string::npos) << error;
  EXPECT_EQ(error.rfind("f.yaml:", 0), 0u) << error;
  EXPECT_LT(seconds, 2.0);
}

TEST(YamlSafety, AFewAliasesAreStillRead) {
  auto parsed = parse_yaml_document("p: &p [1, 2]\nq: *p\nr: {s: *p}\n", "f.yaml");
  ASSERT_TRUE(parsed) << parsed.error().message;
  EXPECT_EQ((*parsed)["q"][1].as<int>(), 2);
  EXPECT_EQ((*parsed)["r"]["s"][0].as<int>(), 1);
}

TEST(YamlSafety, ASecondDocumentIsRefused) {
  EXPECT_EQ(yaml_safety_error("a: 1\n---\nb: 2\n")
                .rfind("f.yaml:2:1: second YAML document: a pkm file holds one", 0),
            0u);
  EXPECT_NE(yaml_safety_error("a: 1\n...\n---\nb: 2\n").find("second YAML document"), std::string::npos);
  // One document, with its markers, is fine.
  EXPECT_EQ(yaml_safety_error("---\na: 1\n...\n"), "(accepted)");
}

TEST(YamlSafety, AnUnclosedQuoteIsBlamedWhereItOpens) {
  const std::string text =
      "type: hexapod\nname: \"ch5\nangles: krylov\n# a \"quoted\" word in a comment\nhome: [0, 0, 700]\n";
  EXPECT_EQ(yaml_safety_error(text),
            "f.yaml:2:7: unclosed quote: the \" opened here is not closed on this line (the next \" is on "
            "line 4); a quoted text must end on the line where it starts");
  EXPECT_EQ(yaml_safety_error("type: x\nname: 'abc\n"),
            "f.yaml:2:7: unclosed quote: the ' opened here is never closed");
  // Escaped and doubled quotes stay inside their text.
  EXPECT_EQ(yaml_safety_error("a: \"say \\\"hi\\\"\"\nb: 'it''s'\nc: it's\n"), "(accepted)");
}

TEST(YamlSafety, AnUnclosedBracketIsBlamedWhereItOpens) {
  // yaml-cpp's own place is the end of the file.
  EXPECT_EQ(yaml_safety_error("type: x\nhome: [1, [2, 3]\n"),
            "f.yaml:2:7: not valid YAML: the [ opened here is never closed with a ]");
  EXPECT_EQ(yaml_safety_error("type: x\nlimits: {a: [1, 2], b: 3\n"),
            "f.yaml:2:9: not valid YAML: the { opened here is never closed with a }");
}

TEST(YamlSafety, ATabInTheIndentationIsNamed) {
  // yaml-cpp says "illegal map value" at the end of the line, or "end of map not found" on the next one.
  EXPECT_EQ(yaml_safety_error("type: x\nlimits:\n\tactuator_max: 5\n"),
            "f.yaml:3:1: not valid YAML: a TAB in the indentation (YAML indents with spaces only)");
  EXPECT_EQ(yaml_safety_error("type: x\nlimits:\n  a: 1\n \tb: 5\n"),
            "f.yaml:4:2: not valid YAML: a TAB in the indentation (YAML indents with spaces only)");
  // A TAB after the key is no indentation.
  EXPECT_EQ(yaml_safety_error("type: x\nhome:\t[1, 2]\n"), "(accepted)");
}

TEST(YamlSafety, ANulByteIsRefusedAtItsPlace) {
  const std::string text = std::string("type: x\nname: a\0tb\n", 18);
  EXPECT_EQ(yaml_safety_error(text).rfind("f.yaml:2:8: not valid YAML: a NUL byte", 0), 0u)
      << yaml_safety_error(text);
}

TEST(YamlSafety, ALabelHasNoControlCharacters) {
  auto root = parse_yaml_document("name: \"red \\e[31m text\"\nok: \"caf\\xe9\"\n", "f.yaml");
  ASSERT_TRUE(root);
  const YamlReader reader("f.yaml");
  auto name = reader.optional_label(*root, "name");
  ASSERT_FALSE(name);
  EXPECT_EQ(name.error().message,
            "f.yaml:1:7: name: a control character (\\x1B) at byte 5: a name is one line of printable text");
  auto latin1 = parse_yaml_document("name: caf\xe9\n", "f.yaml");
  ASSERT_TRUE(latin1);
  EXPECT_EQ(
      reader.optional_label(*latin1, "name").error().message,
      "f.yaml:1:7: name: a byte that is not UTF-8 (\\xE9) at byte 4: a name is one line of UTF-8 text (save "
      "the file as UTF-8)");
  auto ok = reader.optional_label(*root, "ok");
  ASSERT_TRUE(ok);
  EXPECT_EQ(**ok, "caf\xc3\xa9");
}

TEST(YamlSafety, APointCoordinateBeyondAnyMachineIsBlamedOnItsKey) {
  auto root = parse_yaml_document("p: [0, 1e308, 0]\n", "f.yaml");
  ASSERT_TRUE(root);
  auto p = YamlReader("f.yaml").point((*root)["p"], "p", 3);
  ASSERT_FALSE(p);
  EXPECT_EQ(p.error().message,
            "f.yaml:1:8: p[1]: 1e+308 is too large for a coordinate (at most 1e+09 in size)");
}

TEST(YamlSafety, NumbersSayWhatIsWrongWithThem) {
  auto root = parse_yaml_document("a: .inf\nc: 1e999\n", "f.yaml");
  ASSERT_TRUE(root);
  const YamlReader reader("f.yaml");
  EXPECT_EQ(reader.number((*root)["a"], "a").error().message,
            "f.yaml:1:4: a: expected a finite number, got '.inf'");
  EXPECT_EQ(reader.number((*root)["c"], "c").error().message,
            "f.yaml:2:4: c: expected a finite number, got '1e999' (out of range)");
}

TEST(YamlSafety, AHomeAngleBeyondAMillionDegreesIsRefused) {
  const std::string text =
      "type: planar3\nbase_joints:\n  - [0, 200]\n  - [-173.2, -100]\n  - [173.2, -100]\nplatform_joints:\n"
      "  - [0, 100]\n  - [-86.6, -50]\n  - [86.6, -50]\nhome: [0, 0, 1e300]\n";
  auto machine = parse_machine_text(text, "f.yaml");
  ASSERT_FALSE(machine);
  EXPECT_NE(
      machine.error().message.find("f.yaml:10:14: home[2]: an angle of 1e+300 deg is not an orientation"),
      std::string::npos)
      << machine.error().message;
}

}  // namespace
}  // namespace pkm
