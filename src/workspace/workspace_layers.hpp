#pragma once
// The numeric layers of a workspace map, named once: the CSV's columns, the summary's keys and the report's
// heat maps all come from this table, so that they cannot disagree about a name or a unit.
#include <array>
#include <string_view>

#include "workspace/workspace_cell.hpp"

namespace pkm::workspace {

enum class Layer {
  condition_number,     ///< σ_max/σ_min of J (mm and rad)
  error_amplification,  ///< δρ (Smirnov 2019, eq. 145)
  sensitivity_x,        ///< S_x (eq. 144)
  sensitivity_y,        ///< S_y
  sensitivity_z,        ///< S_z
  lowest_stiffness,     ///< N/µm, optional
  lowest_frequency,     ///< Hz, optional
  calibrated_error,     ///< mm, optional
};
inline constexpr int kLayerCount = 8;

struct LayerInfo {
  Layer layer;
  std::string_view column;  ///< the CSV column and summary key, with its unit where it has one
  std::string_view label;   ///< for people: the report's heat map, the CLI's summary
  std::string_view unit;    ///< "" for ratios
  bool optional;            ///< only in maps that asked for it (WorkspaceMapOptions)
};

/// Every layer, in the CSV's column order.
const std::array<LayerInfo, kLayerCount>& workspace_layers();
const LayerInfo& layer_info(Layer layer);

/// The cell's value of a layer (NaN where it has none).
double layer_value(const WorkspaceCell& cell, Layer layer);

}  // namespace pkm::workspace
