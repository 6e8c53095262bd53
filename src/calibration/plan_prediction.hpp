#pragma once
// What a plan will deliver, predicted before measuring: the covariance of the identified
// parameters for a measurement σ (identifiability.hpp: (JᵀJ)⁺ of the plan's weighted Jacobian at the drawing,
// plan_jacobian.hpp) and the tool point's resulting error at held-out poses, sqrt(trace(G·Σ·Gᵀ)) per pose
// with G = ∂ tool point / ∂θ (tool_sensitivity.hpp). This is the error from measurement noise alone: what the
// plan leaves unidentifiable stays at the drawing and adds its own (bias) error, which the prediction does
// not see.
#include <vector>

#include "calibration/identifiability.hpp"
#include "calibration/residuals.hpp"
#include "calibration/synthetic_measurements.hpp"

namespace pkm::calibration {

struct PlanPrediction {
  Identifiability identifiability;  ///< conditioning, dropped combinations, covariance, standard deviations
  std::vector<double> tool_sd_mm;   ///< per held-out pose: sqrt(trace(G·Σ·Gᵀ))
  double tool_rms_mm = 0.0;         ///< rms of tool_sd_mm
  double tool_p90_mm = 0.0;         ///< 90th percentile of tool_sd_mm
  double tool_max_mm = 0.0;
};

/// The prediction for measuring `plan` with `setup` on `nominal`, evaluated at `held_out` poses.
Result<PlanPrediction> predict_plan(const Mechanism& nominal, const std::vector<Pose>& plan,
                                    const MeasurementSetup& setup, const std::vector<Pose>& held_out,
                                    const ResidualOptions& residuals = {},
                                    const IdentifiabilityOptions& identifiability = {});

}  // namespace pkm::calibration
