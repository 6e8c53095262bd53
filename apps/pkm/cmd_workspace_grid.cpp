#include "cmd_workspace_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "core/units.hpp"
#include "io/pose_input.hpp"

namespace pkm::cli {
namespace {

Error workspace_flag_error(const std::string& flag, const std::string& message) {
  return make_error(ErrorCode::bad_input, fmt::format("{}: {}", flag, message));
}

bool same_coordinate_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char p, char q) {
           return std::tolower(static_cast<unsigned char>(p)) == std::tolower(static_cast<unsigned char>(q));
         });
}

// "xy", "xz", "yz", or two of the machine's coordinate names, "x,B" or "z,psi" (any case): their indices.
Result<std::array<int, 2>> workspace_plane_coordinates(const Mechanism& mechanism, const std::string& text) {
  if (auto plane = dynamics::grid_plane_from_string(text); plane) return dynamics::grid_plane_axes(*plane);
  const auto names = pose_coordinate_names(mechanism);
  std::array<int, 2> coordinates{-1, -1};
  const std::size_t comma = text.find(',');
  const std::string_view parts[2] = {
      std::string_view(text).substr(0, comma),
      comma == std::string::npos ? std::string_view() : std::string_view(text).substr(comma + 1)};
  for (int k = 0; k < 2; ++k) {
    for (int c = 0; c < 6; ++c) {
      if (names[static_cast<std::size_t>(c)] != "-" &&
          same_coordinate_name(parts[k], names[static_cast<std::size_t>(c)])) {
        coordinates[static_cast<std::size_t>(k)] = c;
      }
    }
  }
  if (coordinates[0] < 0 || coordinates[1] < 0) {
    return workspace_flag_error(
        "--plane " + text,
        fmt::format("expected xy, xz, yz or two of the coordinates {} separated by a comma (e.g. x,{})",
                    fmt::join(controlled_coordinate_names(mechanism), ", "),
                    controlled_coordinate_names(mechanism).back()));
  }
  return coordinates;
}

}  // namespace

Result<workspace::WorkspaceGrid> workspace_grid_from(const Mechanism& mechanism,
                                                     const WorkspaceGridArguments& arguments) {
  const MapGridArguments& section = arguments.section;
  Pose centre = mechanism.home();
  if (!section.centre_text.empty()) {
    auto values = parse_number_list(section.centre_text, "--centre");
    if (!values) return values.error();
    auto pose = pose_from_user(mechanism, *values, "--centre");
    if (!pose) return pose.error();
    centre = *pose;
  }
  workspace::WorkspaceGrid grid;
  std::string flag = "--grid3d";
  if (arguments.grid3d) {
    grid = workspace::position_grid(centre, section.half_range_mm, section.step_mm);
  } else {
    auto coordinates = workspace_plane_coordinates(mechanism, section.plane);
    if (!coordinates) return coordinates.error();
    grid.centre = centre;
    for (int c : *coordinates) {
      const bool angle = c >= 3;
      grid.axes.push_back({c, angle ? rad_from_deg(arguments.half_range_deg) : section.half_range_mm,
                           angle ? rad_from_deg(arguments.step_deg) : section.step_mm});
    }
    flag = "--plane " + section.plane;
  }
  // The size first, with the flags that set it: a mistyped step is the usual cause.
  double cells = 1.0;
  bool angles = false;
  for (const workspace::GridAxis& axis : grid.axes) {
    cells *= dynamics::grid_points_per_axis(axis.half_range_mm_or_rad, axis.step_mm_or_rad);
    angles = angles || axis.coordinate >= 3;
  }
  if (cells > kMaxMapGridPoints) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{} gives {:.4g} cells, more than {:.0f}; take a larger {} or a smaller {}",
                                  describe_workspace_grid(mechanism, grid), cells, kMaxMapGridPoints,
                                  angles ? "--step-mm / --step-deg" : "--step-mm",
                                  angles ? "--range-mm / --range-deg" : "--range-mm"));
  }
  if (Status valid = workspace::validate_grid(mechanism, grid, kMaxMapGridPoints); !valid) {
    return workspace_flag_error(flag, valid.error().message);
  }
  return grid;
}

std::string describe_workspace_grid(const Mechanism& mechanism, const workspace::WorkspaceGrid& grid) {
  const auto names = pose_coordinate_names(mechanism);
  std::string axes, extents;
  for (const workspace::GridAxis& axis : grid.axes) {
    const bool angle = axis.coordinate >= 3;
    const double scale = angle ? deg_from_rad(1.0) : 1.0;
    axes += names[static_cast<std::size_t>(axis.coordinate)];
    if (!extents.empty()) extents += ", ";
    fmt::format_to(std::back_inserter(extents), "{} ±{:g} {} by {:g}",
                   names[static_cast<std::size_t>(axis.coordinate)], axis.half_range_mm_or_rad * scale,
                   angle ? "deg" : "mm", axis.step_mm_or_rad * scale);
  }
  const std::string what =
      grid.axes.size() == 3 ? std::string("the 3-D grid about") : fmt::format("the {} section through", axes);
  return fmt::format("{} {} ({})", what, map_pose_text(mechanism, grid.centre), extents);
}

}  // namespace pkm::cli
