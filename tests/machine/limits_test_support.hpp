#pragma once
// The chapter-5 hexapod as machine-file text, without limits or motion, for the tests of the machine file's
// `limits:` and `motion:` sections: a test appends its own section and knows the line it starts on.
#include <algorithm>
#include <string>

namespace pkm::test {

inline const char* kCh5HexapodText = R"(type: hexapod
angles: krylov
base_joints:
  - [400.0, 0.0, 0.0]
  - [200.0, 346.41016151377545, 0.0]
  - [-200.0, 346.41016151377545, 0.0]
  - [-400.0, 0.0, 0.0]
  - [-200.0, -346.41016151377545, 0.0]
  - [200.0, -346.41016151377545, 0.0]
platform_joints:
  - [173.20508075688772, 100, 0]
  - [173.20508075688772, 100, 0]
  - [-173.20508075688772, 100, 0]
  - [-173.20508075688772, 100, 0]
  - [0, -200, 0]
  - [0, -200, 0]
tool: [0, 0, 150]
home: [0, 0, 700, 0, 0, 0]
)";

/// The 1-based line on which text appended to `text` starts.
inline int appended_line(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
}

}  // namespace pkm::test
