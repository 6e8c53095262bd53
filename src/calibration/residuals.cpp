#include "calibration/residuals.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

#include "calibration/pose_fit.hpp"

namespace pkm::calibration {

namespace {

std::string pose_label(const MeasuredPose& pose, int index) {
  std::string label = pose.id.empty() ? fmt::format("pose {}", index + 1) : fmt::format("pose '{}'", pose.id);
  if (pose.line > 0) label += fmt::format(" (line {})", pose.line);
  return label;
}

// ∂IK/∂twist at `pose`: the mechanism's own twist Jacobian, else central differences of its IK (steps of 1e-6
// mm and 1e-6 rad: the derivative only weights the residuals, so 1e-8 relative is ample).
bool actuator_twist_jacobian(const Mechanism& mechanism, const Pose& pose, Eigen::MatrixXd& out) {
  JacobianMatrix j;
  if (mechanism.twist_jacobian(pose, j)) {
    out = j;
    return true;
  }
  constexpr double kStep = 1e-6;
  const int n = mechanism.actuator_count();
  out.resize(n, 6);
  ActuatorVector plus(n), minus(n);
  for (int c = 0; c < 6; ++c) {
    Pose a = pose;
    Pose b = pose;
    if (c < 3) {
      a.position_mm[c] += kStep;
      b.position_mm[c] -= kStep;
    } else {
      const Eigen::Vector3d axis = Eigen::Vector3d::Unit(c - 3);
      a.rotation = Eigen::AngleAxisd(kStep, axis).toRotationMatrix() * pose.rotation;
      b.rotation = Eigen::AngleAxisd(-kStep, axis).toRotationMatrix() * pose.rotation;
    }
    if (!mechanism.actuator_values(a, plus.data()) || !mechanism.actuator_values(b, minus.data()))
      return false;
    out.col(c) = (plus - minus) / (2.0 * kStep);
  }
  return true;
}

Status check_sigma(double sigma_mm, const std::string& where) {
  if (sigma_mm > 0.0 && std::isfinite(sigma_mm)) return ok_status();
  return make_error(ErrorCode::bad_input,
                    fmt::format("{}: a measurement's sigma is {} mm; it must be > 0", where, sigma_mm));
}

// FK of `readings` on `mechanism` from `guess`, else from the home pose.
Result<Pose> solve_forward(const Mechanism& mechanism, const ActuatorVector& readings, const Pose& guess,
                           const FkOptions& options) {
  auto solution = mechanism.forward(readings, guess, options);
  if (!solution) solution = mechanism.forward(readings, mechanism.home(), options);
  if (!solution) return solution.error();
  return solution->pose;
}

// The ballbar's distances at pose i: one row each, weighted by 1/σ.
Result<ResidualBlock> ballbar_block(const MeasuredPose& measured, int i, int first_row,
                                    const std::string& where) {
  ResidualBlock block;
  block.pose = i;
  block.form = ResidualForm::ballbar_forward;
  block.first_row = first_row;
  block.rows = static_cast<int>(measured.distances.size());
  block.whitening = Eigen::MatrixXd::Zero(block.rows, block.rows);
  for (int k = 0; k < block.rows; ++k) {
    const double sigma = measured.distances[static_cast<std::size_t>(k)].sigma_mm;
    if (auto ok = check_sigma(sigma, where); !ok) return ok.error();
    block.whitening(k, k) = 1.0 / sigma;
  }
  return block;
}

}  // namespace

ResidualModel ResidualModel::at_commanded_poses() const {
  ResidualModel copy = *this;
  for (ResidualBlock& b : copy.blocks_) {
    if (b.form == ResidualForm::pose_inverse) b.fitted_pose = b.commanded_pose;
  }
  return copy;
}

int ResidualModel::count(ResidualForm form) const {
  int n = 0;
  for (const ResidualBlock& b : blocks_) n += b.form == form ? 1 : 0;
  return n;
}

Result<ResidualModel> ResidualModel::make(const Mechanism& nominal, const MeasurementSet& data,
                                          const ResidualOptions& options) {
  ResidualModel model;
  model.data_ = data;
  model.options_ = options;
  const int actuators = nominal.actuator_count();
  const bool full_pose_mechanism = nominal.controlled_axes().count() == 6;
  Pose previous = nominal.home();
  for (int i = 0; i < static_cast<int>(data.poses.size()); ++i) {
    const MeasuredPose& measured = data.poses[static_cast<std::size_t>(i)];
    const std::string where = pose_label(measured, i);
    if (measured.readings.size() != actuators) {
      return make_error(ErrorCode::bad_input,
                        fmt::format("{}: {} drive readings for a mechanism with {} actuators", where,
                                    measured.readings.size(), actuators));
    }
    if (measured.targets.empty() && measured.distances.empty()) {
      return make_error(ErrorCode::bad_input, fmt::format("{}: nothing was measured there", where));
    }
    Pose start = previous;
    if (!measured.targets.empty()) {
      auto pairs = target_pairs(data.fixture, measured.targets);
      if (!pairs)
        return make_error(ErrorCode::bad_input, fmt::format("{}: {}", where, pairs.error().message));
      for (const TargetPair& p : *pairs) {
        if (auto ok = check_sigma(p.sigma_mm, where); !ok) return ok.error();
      }
      std::optional<PoseFit> fit;
      if (pairs->size() >= 3 && targets_span_plane(*pairs)) {
        auto fitted = fit_pose(*pairs);
        if (!fitted)
          return make_error(fitted.error().code, fmt::format("{}: {}", where, fitted.error().message));
        fit = *fitted;
        start = fit->pose;
      }
      ResidualBlock block;
      block.pose = i;
      block.first_row = model.rows_;
      if (fit && full_pose_mechanism && options.pose_inverse_where_possible) {
        block.form = ResidualForm::pose_inverse;
        block.rows = actuators;
        block.fitted_pose = fit->pose;
        Eigen::MatrixXd j;
        if (!actuator_twist_jacobian(nominal, fit->pose, j)) {
          return make_error(
              ErrorCode::unreachable,
              fmt::format("{}: the pose fitted to the targets is out of reach of the model", where));
        }
        const Eigen::MatrixXd covariance = j * fit->covariance * j.transpose();
        const Eigen::LLT<Eigen::MatrixXd> llt(covariance);
        if (llt.info() != Eigen::Success) {
          return make_error(ErrorCode::singular,
                            fmt::format("{}: the targets do not determine the actuators there", where));
        }
        block.whitening = llt.matrixL().solve(Eigen::MatrixXd::Identity(actuators, actuators));
      } else {
        block.form = ResidualForm::targets_forward;
        block.rows = 3 * static_cast<int>(pairs->size());
        block.whitening = Eigen::MatrixXd::Zero(block.rows, block.rows);
        for (std::size_t k = 0; k < pairs->size(); ++k) {
          const double w = 1.0 / (*pairs)[k].sigma_mm;
          block.whitening.block<3, 3>(3 * static_cast<Eigen::Index>(k), 3 * static_cast<Eigen::Index>(k)) =
              w * Eigen::Matrix3d::Identity();
        }
      }
      model.rows_ += block.rows;
      model.blocks_.push_back(std::move(block));
    }
    if (!measured.distances.empty()) {
      auto block = ballbar_block(measured, i, model.rows_, where);
      if (!block) return block.error();
      model.rows_ += block->rows;
      model.blocks_.push_back(std::move(*block));
    }
    // Every pose gets its nominal FK: the forward forms start from it, pose_inverse blocks keep it as the
    // commanded pose (at_commanded_poses); their fitted pose is a close guess.
    {
      auto solved = solve_forward(nominal, measured.readings, start, options.fk);
      if (!solved && !(start.position_mm - previous.position_mm).isZero()) {
        solved = solve_forward(nominal, measured.readings, previous, options.fk);
      }
      if (!solved) {
        return make_error(solved.error().code,
                          fmt::format("{}: the nominal model has no forward solution for the readings ({})",
                                      where, solved.error().message));
      }
      start = *solved;
    }
    for (ResidualBlock& b : model.blocks_) {
      if (b.pose == i) b.commanded_pose = start;
    }
    model.start_poses_.push_back(start);
    previous = start;
  }
  return model;
}

Status ResidualModel::evaluate(const Mechanism& mechanism, std::vector<Pose>& poses, Eigen::VectorXd& raw,
                               Eigen::VectorXd* weighted) const {
  raw.resize(rows_);
  ActuatorVector values(mechanism.actuator_count());
  int solved_pose = -1;  // the pose whose forward kinematics is in poses[] for this call
  for (const ResidualBlock& block : blocks_) {
    const MeasuredPose& measured = data_.poses[static_cast<std::size_t>(block.pose)];
    auto r = raw.segment(block.first_row, block.rows);
    if (block.form == ResidualForm::pose_inverse) {
      if (!mechanism.actuator_values(block.fitted_pose, values.data())) {
        return make_error(
            ErrorCode::unreachable,
            fmt::format("{}: out of reach of the model being identified", pose_label(measured, block.pose)));
      }
      r = values - measured.readings;
      continue;
    }
    Pose& pose = poses[static_cast<std::size_t>(block.pose)];
    if (solved_pose != block.pose) {
      auto solution = mechanism.forward(measured.readings, pose, options_.fk);
      if (!solution) {
        return make_error(solution.error().code,
                          fmt::format("{}: {}", pose_label(measured, block.pose), solution.error().message));
      }
      pose = solution->pose;
      solved_pose = block.pose;
    }
    if (block.form == ResidualForm::targets_forward) {
      for (std::size_t k = 0; k < measured.targets.size(); ++k) {
        const TargetObservation& o = measured.targets[k];
        r.segment<3>(3 * static_cast<Eigen::Index>(k)) =
            o.position_mm - pose.to_base(data_.fixture[static_cast<std::size_t>(o.target)].position_mm);
      }
    } else {
      const double distance = (pose.position_mm - data_.ballbar_centre_mm).norm();
      for (int k = 0; k < block.rows; ++k)
        r[k] = distance - measured.distances[static_cast<std::size_t>(k)].distance_mm;
    }
  }
  if (weighted) {
    weighted->resize(rows_);
    for (const ResidualBlock& block : blocks_) {
      weighted->segment(block.first_row, block.rows).noalias() =
          block.whitening * raw.segment(block.first_row, block.rows);
    }
  }
  return ok_status();
}

}  // namespace pkm::calibration
