#include "calibration/plan_design.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <numbers>
#include <random>

#include "calibration/plan_jacobian.hpp"

namespace pkm::calibration {

namespace {

bool accepted(const PoseFilter& accept, const Pose& pose, const ActuatorVector& actuators) {
  return !accept || accept(pose, actuators);
}

// log det(I + J_c·M⁻¹·J_cᵀ): how much measuring pose c adds to log det M (the matrix determinant lemma).
double log_det_gain(const Eigen::MatrixXd& pose_rows, const Eigen::LDLT<Eigen::MatrixXd>& information) {
  const Eigen::MatrixXd inner = Eigen::MatrixXd::Identity(pose_rows.rows(), pose_rows.rows()) +
                                pose_rows * information.solve(pose_rows.transpose());
  const Eigen::VectorXd d = inner.ldlt().vectorD();
  return d.array().max(1e-300).log().sum();
}

}  // namespace

Result<PosePlan> seven_pose_plan(const Mechanism& nominal, double strut_change_mm, const PoseFilter& accept) {
  PosePlan plan{"seven_pose", {nominal.home()}};
  auto readings = nominal.inverse(nominal.home());
  if (!readings) return make_error(readings.error().code, fmt::format("home: {}", readings.error().message));
  if (!accepted(accept, nominal.home(), *readings)) {
    return make_error(ErrorCode::limit_exceeded,
                      "the seven-pose plan starts at home, which the limits refuse");
  }
  ActuatorVector lengths = *readings;
  for (int j = 0; j < nominal.actuator_count(); ++j) {
    lengths[j] += strut_change_mm;
    auto reached = nominal.forward(lengths, plan.poses.back());
    if (!reached) {
      return make_error(reached.error().code,
                        fmt::format("the seven-pose plan after changing strut {} by {} mm: {}", j + 1,
                                    strut_change_mm, reached.error().message));
    }
    if (!accepted(accept, reached->pose, lengths)) {
      return make_error(ErrorCode::limit_exceeded,
                        fmt::format("the seven-pose plan after changing strut {} by {} mm leaves the limits",
                                    j + 1, strut_change_mm));
    }
    plan.poses.push_back(reached->pose);
  }
  return plan;
}

Result<PosePlan> random_plan(const Mechanism& nominal, int count, const PoseBox& box, std::uint64_t seed,
                             const PoseFilter& accept) {
  PosePlan plan{"random", {}};
  if (count < 1) return make_error(ErrorCode::bad_input, fmt::format("a plan needs poses, {} asked", count));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const AxisMask axes = nominal.controlled_axes();
  const PoseVector centre = vector_from_pose(nominal.convention(), nominal.home());
  const long attempts = 1000L * count;
  for (long a = 0; a < attempts && static_cast<int>(plan.poses.size()) < count; ++a) {
    PoseVector v = centre;
    for (int i = 0; i < 6; ++i) {
      // Every coordinate draws, controlled or not, so that a plan does not depend on which ones are.
      const double offset = unit(rng) * (i < 3 ? box.translation_mm : box.angle_rad);
      if (axes.controlled[static_cast<std::size_t>(i)]) v[i] += offset;
    }
    auto pose = nominal.complete_pose(pose_from_vector(nominal.convention(), v));
    if (!pose) continue;
    auto actuators = nominal.inverse(*pose);
    if (!actuators || !accepted(accept, *pose, *actuators)) continue;
    plan.poses.push_back(*pose);
  }
  if (static_cast<int>(plan.poses.size()) < count) {
    return make_error(
        ErrorCode::limit_exceeded,
        fmt::format("only {} of {} random poses within ±{} mm, ±{:.3g}° of home are reachable and "
                    "within the limits",
                    plan.poses.size(), count, box.translation_mm, box.angle_rad * 180.0 / std::numbers::pi));
  }
  return plan;
}

Result<PosePlan> d_optimal_plan(const Mechanism& nominal, const MeasurementSetup& setup, int count,
                                const DOptimalOptions& options) {
  if (count < 1) return make_error(ErrorCode::bad_input, fmt::format("a plan needs poses, {} asked", count));
  if (options.candidates < count) {
    return make_error(ErrorCode::bad_input,
                      fmt::format("{} candidates cannot give a plan of {} poses", options.candidates, count));
  }
  auto candidates = random_plan(nominal, options.candidates, options.box, options.seed, options.accept);
  if (!candidates) return candidates.error();
  auto plan_j = plan_jacobian(nominal, candidates->poses, setup, options.residuals);
  if (!plan_j) return plan_j.error();
  // The subspace every candidate together can identify: directions no pose sees add nothing to any choice.
  const Identifiability all =
      analyse_identifiability(plan_j->jacobian, plan_j->layout, options.identifiability);
  const Eigen::MatrixXd basis = all.identifiable_basis();
  const int k = all.rank;
  const int n = options.candidates;
  std::vector<Eigen::MatrixXd> rows(static_cast<std::size_t>(n));
  for (int c = 0; c < n; ++c) {
    const auto i = static_cast<std::size_t>(c);
    rows[i] = plan_j->jacobian.middleRows(plan_j->first_row[i], plan_j->rows[i]) * basis;
  }
  // A small ridge keeps M invertible while the first poses cannot yet see every direction; 1e-9 of the
  // strongest direction's information per candidate is far below any pose's contribution.
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(k, k);
  for (const auto& r : rows) full.noalias() += r.transpose() * r;
  const double ridge = 1e-9 * (k > 0 ? full.diagonal().maxCoeff() : 1.0) / n;
  Eigen::MatrixXd information = ridge * Eigen::MatrixXd::Identity(k, k);

  std::vector<bool> chosen(static_cast<std::size_t>(n), false);
  std::vector<int> selection;
  for (int s = 0; s < count; ++s) {
    const Eigen::LDLT<Eigen::MatrixXd> m(information);
    int best = -1;
    double best_gain = -1.0;
    for (int c = 0; c < n; ++c) {
      if (chosen[static_cast<std::size_t>(c)]) continue;
      const double gain = log_det_gain(rows[static_cast<std::size_t>(c)], m);
      if (gain > best_gain) {
        best_gain = gain;
        best = c;
      }
    }
    chosen[static_cast<std::size_t>(best)] = true;
    selection.push_back(best);
    information.noalias() +=
        rows[static_cast<std::size_t>(best)].transpose() * rows[static_cast<std::size_t>(best)];
  }
  // Exchange: take a chosen pose out, put in the candidate that adds most, while that beats the pose itself.
  for (int pass = 0; pass < options.exchange_passes; ++pass) {
    bool improved = false;
    for (int& slot : selection) {
      const Eigen::MatrixXd& out = rows[static_cast<std::size_t>(slot)];
      const Eigen::MatrixXd without = information - out.transpose() * out;
      const Eigen::LDLT<Eigen::MatrixXd> m(without);
      const double keep_gain = log_det_gain(out, m);
      int best = -1;
      double best_gain = keep_gain * (1.0 + 1e-9) + 1e-12;
      for (int c = 0; c < n; ++c) {
        if (chosen[static_cast<std::size_t>(c)]) continue;
        const double gain = log_det_gain(rows[static_cast<std::size_t>(c)], m);
        if (gain > best_gain) {
          best_gain = gain;
          best = c;
        }
      }
      if (best < 0) continue;
      chosen[static_cast<std::size_t>(slot)] = false;
      chosen[static_cast<std::size_t>(best)] = true;
      information =
          without + rows[static_cast<std::size_t>(best)].transpose() * rows[static_cast<std::size_t>(best)];
      slot = best;
      improved = true;
    }
    if (!improved) break;
  }
  PosePlan plan{"d_optimal", {}};
  for (int c : selection) plan.poses.push_back(candidates->poses[static_cast<std::size_t>(c)]);
  return plan;
}

}  // namespace pkm::calibration
