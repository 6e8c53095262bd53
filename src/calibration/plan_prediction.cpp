#include "calibration/plan_prediction.hpp"

#include <algorithm>
#include <cmath>

#include "calibration/plan_jacobian.hpp"
#include "calibration/statistics.hpp"
#include "calibration/tool_sensitivity.hpp"

namespace pkm::calibration {

Result<PlanPrediction> predict_plan(const Mechanism& nominal, const std::vector<Pose>& plan,
                                    const MeasurementSetup& setup, const std::vector<Pose>& held_out,
                                    const ResidualOptions& residuals,
                                    const IdentifiabilityOptions& identifiability) {
  auto plan_j = plan_jacobian(nominal, plan, setup, residuals);
  if (!plan_j) return plan_j.error();
  PlanPrediction prediction;
  prediction.identifiability = analyse_identifiability(plan_j->jacobian, plan_j->layout, identifiability);
  auto g = tool_point_sensitivities(nominal, plan_j->layout, parameter_vector(plan_j->layout.groups),
                                    held_out, residuals);
  if (!g) return g.error();
  const Eigen::MatrixXd& covariance = prediction.identifiability.covariance;
  for (const ToolSensitivity& gp : *g) {
    const Eigen::Matrix3d tool_covariance = gp * covariance * gp.transpose();
    prediction.tool_sd_mm.push_back(std::sqrt(std::max(0.0, tool_covariance.trace())));
  }
  prediction.tool_rms_mm = root_mean_square(prediction.tool_sd_mm);
  prediction.tool_p90_mm = quantile(prediction.tool_sd_mm, 0.9);
  prediction.tool_max_mm = prediction.tool_sd_mm.empty() ? 0.0
                                                         : *std::max_element(prediction.tool_sd_mm.begin(),
                                                                             prediction.tool_sd_mm.end());
  return prediction;
}

}  // namespace pkm::calibration
