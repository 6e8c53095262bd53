#pragma once
// For the tests of the machine file's `limits:` and `motion:` sections: a test appends its own section to the
// ch5 hexapod's text (test_support.hpp, kCh5HexapodText) and knows the line it starts on.
#include <algorithm>
#include <string>

#include "test_support.hpp"

namespace pkm::test {

/// The 1-based line on which text appended to `text` starts.
inline int appended_line(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
}

}  // namespace pkm::test
