// The one YAML reader: keys given twice and keys that are lists are refused with file, line, column and key
// (yaml-cpp keeps the first of a duplicate silently, and a list as a key made pkm abort); deep nesting and
// empty values are reported where they are.
#include <gtest/gtest.h>

#include <string>

#include "io/machine_file.hpp"
#include "io/yaml_reader.hpp"

namespace {

std::string yaml_document_error(const std::string& text) {
  auto document = pkm::parse_yaml_document(text, "m.yaml");
  return document ? std::string("(accepted)") : document.error().message;
}

TEST(YamlDocument, RefusesAKeyGivenTwice) {
  EXPECT_EQ(yaml_document_error("a: 1\nb: 2\na: 3\n"), "m.yaml:3:1: a: given twice (first on line 1)");
  EXPECT_EQ(yaml_document_error("limits:\n  min: 1\n  min: 2\n"),
            "m.yaml:3:3: limits.min: given twice (first on line 2)");
  EXPECT_EQ(yaml_document_error("blocks:\n  - {a: 1, a: 2}\n"),
            "m.yaml:2:12: blocks[0].a: given twice (first on line 2)");
}

TEST(YamlDocument, RefusesKeysThatAreNotWords) {
  EXPECT_EQ(yaml_document_error("type: tripod\n[a]: 1\n"),
            "m.yaml:2:1: (top level): a key must be a plain word, not a list");
  EXPECT_EQ(yaml_document_error("limits:\n  {a: 1}: 2\n"),
            "m.yaml:2:3: limits: a key must be a plain word, not a mapping");
}

TEST(YamlDocument, DeepNestingIsNamedWithItsPlace) {
  std::string deep = "home: ";  // appended, not "a" + std::string(n, c): GCC 12 warns falsely on that
  deep.append(3000, '[');
  const std::string message = yaml_document_error(deep + "\n");
  EXPECT_NE(message.find("m.yaml:1:"), std::string::npos) << message;
  EXPECT_NE(message.find("nested more than"), std::string::npos) << message;
}

TEST(YamlDocument, SyntaxErrorsHaveLineAndColumn) {
  EXPECT_EQ(yaml_document_error("a: [1, 2\n").rfind("m.yaml:", 0), 0u);
  EXPECT_NE(yaml_document_error("a: [1, 2\n").find("not valid YAML"), std::string::npos);
}

TEST(YamlDocument, MachineFileErrorsPointAtTheKeyOfAnEmptyValue) {
  const auto machine =
      pkm::parse_machine_text("type: planar2\nbase_joints: [[0, 0], [300, 40]]\nhome:\n", "m.yaml");
  ASSERT_FALSE(machine);
  EXPECT_EQ(machine.error().message.rfind("m.yaml:3:1: home: ", 0), 0u) << machine.error().message;
}

TEST(YamlDocument, MachineNameMustBeText) {
  const auto machine =
      pkm::parse_machine_text("name: [1, 2]\ntype: planar2\nbase_joints: [[0, 0], [300, 40]]\n", "m.yaml");
  ASSERT_FALSE(machine);
  EXPECT_EQ(machine.error().message, "m.yaml:1:7: name: expected a word or a text, not a list");
}

}  // namespace
