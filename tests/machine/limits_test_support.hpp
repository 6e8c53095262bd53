#pragma once
// For the tests of the machine file's `limits:` and `motion:` sections: a test appends its own section to the
// ch5 hexapod's text (test_support.hpp, kCh5HexapodText) and knows the line it starts on.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "test_support.hpp"

namespace pkm::test {

/// The 1-based line on which text appended to `text` starts.
inline int appended_line(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
}

/// The loader's message for `base` with a section `extra` appended (file name test.yaml); fails the test if
/// the file loads or the error is not bad input.
inline std::string appended_section_error(const std::string& base, const std::string& extra) {
  auto m = parse_machine_text(base + extra, "test.yaml");
  if (m) {
    ADD_FAILURE() << "expected an error for:\n" << extra;
    return {};
  }
  EXPECT_EQ(m.error().code, ErrorCode::bad_input);
  return m.error().message;
}

}  // namespace pkm::test
