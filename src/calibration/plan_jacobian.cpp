#include "calibration/plan_jacobian.hpp"

#include "calibration/parameter_jacobian.hpp"

namespace pkm::calibration {

Result<PlanJacobian> plan_jacobian(const Mechanism& nominal, const std::vector<Pose>& poses,
                                   const MeasurementSetup& setup, const ResidualOptions& options) {
  auto layout = parameter_layout(nominal);
  if (!layout) return layout.error();
  auto data = simulate_measurements(nominal, nominal, poses, setup, nullptr);
  if (!data) return data.error();
  auto residuals = ResidualModel::make(nominal, *data, options);
  if (!residuals) return residuals.error();
  auto jacobian = residual_jacobian(*residuals, nominal, *layout, parameter_vector(layout->groups),
                                    residuals->start_poses());
  if (!jacobian) return jacobian.error();
  PlanJacobian plan;
  plan.layout = std::move(*layout);
  plan.jacobian = std::move(*jacobian);
  plan.first_row.assign(poses.size(), 0);
  plan.rows.assign(poses.size(), 0);
  for (const ResidualBlock& block : residuals->blocks()) {
    const auto p = static_cast<std::size_t>(block.pose);
    if (plan.rows[p] == 0) plan.first_row[p] = block.first_row;
    plan.rows[p] += block.rows;
  }
  return plan;
}

}  // namespace pkm::calibration
