#include "workspace/workspace_layers.hpp"

namespace pkm::workspace {

const std::array<LayerInfo, kLayerCount>& workspace_layers() {
  // δρ and S are mm of tool point per mm of equal actuator error (per rad for angular actuators): ratios.
  static const std::array<LayerInfo, kLayerCount> layers{{
      {Layer::condition_number, "condition_number", "condition number of J", "", false},
      {Layer::error_amplification, "delta_rho", "error amplification δρ", "", false},
      {Layer::sensitivity_x, "S_x", "sensitivity sum S_x", "", false},
      {Layer::sensitivity_y, "S_y", "sensitivity sum S_y", "", false},
      {Layer::sensitivity_z, "S_z", "sensitivity sum S_z", "", false},
      {Layer::lowest_stiffness, "lowest_stiffness_N_um", "lowest translational stiffness", "N/µm", true},
      {Layer::lowest_frequency, "lowest_frequency_Hz", "lowest natural frequency", "Hz", true},
      {Layer::calibrated_error, "calibrated_error_mm", "predicted error after calibration", "mm", true},
  }};
  return layers;
}

const LayerInfo& layer_info(Layer layer) {
  return workspace_layers()[static_cast<std::size_t>(layer)];
}

double layer_value(const WorkspaceCell& cell, Layer layer) {
  switch (layer) {
    case Layer::condition_number:
      return cell.condition_number;
    case Layer::error_amplification:
      return cell.error_amplification;
    case Layer::sensitivity_x:
      return cell.sensitivity_sums.x();
    case Layer::sensitivity_y:
      return cell.sensitivity_sums.y();
    case Layer::sensitivity_z:
      return cell.sensitivity_sums.z();
    case Layer::lowest_stiffness:
      return cell.lowest_stiffness_N_um;
    case Layer::lowest_frequency:
      return cell.lowest_frequency_Hz;
    case Layer::calibrated_error:
      return cell.calibrated_error_mm;
  }
  return WorkspaceCell::kNone;
}

}  // namespace pkm::workspace
