#pragma once
// What the workspace-map tests share: the ch5 hexapod with its outputs at the pole C (no tool), a map that
// fails the test when it cannot be made, level poses.
#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>
#include <string>

#include "test_support.hpp"
#include "workspace/workspace_map.hpp"

namespace pkm::test {

/// The ch5 hexapod (examples/machines/hexapod_ch5.yaml, its limits included) with the outputs at the pole C:
/// no tool, home at z = 500 mm (as machine/conditioning_test.cpp; Smirnov 2019, §5.2.2's "outputs of C").
inline std::string ws_ch5_pole_text() {
  std::ifstream in(source_path("examples/machines/hexapod_ch5.yaml"));
  std::string yaml, line;
  while (std::getline(in, line)) {
    if (line.rfind("tool:", 0) == 0) line = "tool: [0, 0, 0]";
    if (line.rfind("home:", 0) == 0) line = "home: [0, 0, 500, 0, 0, 0]";
    yaml += line;
    yaml += '\n';
  }
  return yaml;
}

inline Pose ws_level_pose(double x_mm, double y_mm, double z_mm) {
  Pose p;
  p.position_mm = {x_mm, y_mm, z_mm};
  return p;
}

/// The map, or a fatal test failure with the library's message.
inline workspace::WorkspaceMap ws_map_of(const Machine& machine, const workspace::WorkspaceGrid& grid,
                                         const workspace::WorkspaceMapOptions& options = {}) {
  auto map = workspace::workspace_map(machine, grid, options);
  if (!map) {
    ADD_FAILURE() << map.error().message;
    throw std::runtime_error(map.error().message);
  }
  return std::move(map.value());
}

}  // namespace pkm::test
