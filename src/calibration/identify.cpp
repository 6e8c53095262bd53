#include "calibration/identify.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <unsupported/Eigen/LevenbergMarquardt>

#include "calibration/parameter_jacobian.hpp"

namespace pkm::calibration {

namespace {

// Residuals of a trial step whose model has no solution at some pose: large, so that the step is rejected and
// the trust region shrinks (MINPACK has no "undefined here" answer short of stopping).
constexpr double kUnreachableResidual = 1e10;

// The problem in the identifiable subspace: θ(z) = θ0 + S·V_k·z (S the parameter scales, V_k the kept right
// singular vectors at the drawing).
struct SubspaceProblem : Eigen::DenseFunctor<double> {
  SubspaceProblem(const ResidualModel& residual_model, const Mechanism& model_mechanism,
                  const ParameterLayout& layout_in, Eigen::VectorXd start_values, Eigen::MatrixXd subspace)
      : Eigen::DenseFunctor<double>(static_cast<int>(subspace.cols()), residual_model.rows()),
        residuals(residual_model),
        model(model_mechanism),
        layout(layout_in),
        start(std::move(start_values)),
        basis(std::move(subspace)),
        poses(residual_model.start_poses()) {}

  Eigen::VectorXd parameters(const Eigen::VectorXd& z) const {
    return start + layout.scale.cwiseProduct(basis * z);
  }

  int operator()(const Eigen::VectorXd& z, Eigen::VectorXd& f) {
    ++evaluations;
    auto mechanism = mechanism_with_parameters(model, layout, parameters(z));
    std::vector<Pose> trial = poses;
    Eigen::VectorXd raw;
    if (!mechanism || !residuals.evaluate(**mechanism, trial, raw, &f)) {
      f.setConstant(residuals.rows(), kUnreachableResidual);
      return 0;
    }
    poses = std::move(trial);
    return 0;
  }

  int df(const Eigen::VectorXd& z, Eigen::MatrixXd& j) {
    ++jacobians;
    auto full = residual_jacobian(residuals, model, layout, parameters(z), poses);
    if (!full) {
      failure = full.error();
      return -1;
    }
    j.noalias() = *full * basis;
    return 0;
  }

  const ResidualModel& residuals;
  const Mechanism& model;
  const ParameterLayout& layout;
  Eigen::VectorXd start;
  Eigen::MatrixXd basis;
  std::vector<Pose> poses;  ///< FK starts: the solutions of the last successful evaluation
  std::optional<Error> failure;
  int evaluations = 0;
  int jacobians = 0;
};

bool solver_converged(Eigen::LevenbergMarquardtSpace::Status status) {
  using S = Eigen::LevenbergMarquardtSpace::Status;
  switch (status) {
    case S::RelativeReductionTooSmall:
    case S::RelativeErrorTooSmall:
    case S::RelativeErrorAndReductionTooSmall:
    case S::CosinusTooSmall:
    case S::FtolTooSmall:
    case S::XtolTooSmall:
    case S::GtolTooSmall:
      return true;
    default:
      return false;
  }
}

std::string solver_text(Eigen::LevenbergMarquardtSpace::Status status) {
  using S = Eigen::LevenbergMarquardtSpace::Status;
  switch (status) {
    case S::RelativeReductionTooSmall:
      return "the sum of squares no longer decreases";
    case S::RelativeErrorTooSmall:
      return "the step is below the tolerance";
    case S::RelativeErrorAndReductionTooSmall:
      return "the sum of squares no longer decreases and the step is below the tolerance";
    case S::CosinusTooSmall:
    case S::GtolTooSmall:
      return "the residuals are orthogonal to the Jacobian";
    case S::FtolTooSmall:
    case S::XtolTooSmall:
      return "no further improvement is possible at machine precision";
    case S::TooManyFunctionEvaluation:
      return "the limit of residual evaluations was reached";
    case S::UserAsked:
      return "the Jacobian could not be computed";
    default:
      return "the solver rejected its input";
  }
}

Status residuals_at(const ResidualModel& residuals, const Mechanism& nominal, const ParameterLayout& layout,
                    const Eigen::VectorXd& parameters, std::vector<Pose>& poses, Eigen::VectorXd& raw,
                    Eigen::VectorXd& weighted) {
  auto mechanism = mechanism_with_parameters(nominal, layout, parameters);
  if (!mechanism) return mechanism.error();
  return residuals.evaluate(**mechanism, poses, raw, &weighted);
}

}  // namespace

const char* to_string(IdentificationStatus status) {
  switch (status) {
    case IdentificationStatus::identified:
      return "identified";
    case IdentificationStatus::partially_identified:
      return "partially identified";
    case IdentificationStatus::not_converged:
      return "not converged";
  }
  return "?";
}

ResidualSummary summarize_residuals(const Eigen::VectorXd& weighted, const Eigen::VectorXd& raw) {
  ResidualSummary s;
  if (weighted.size() > 0) {
    s.weighted_rms = std::sqrt(weighted.squaredNorm() / static_cast<double>(weighted.size()));
    s.weighted_max = weighted.cwiseAbs().maxCoeff();
  }
  if (raw.size() > 0) {
    s.rms_mm = std::sqrt(raw.squaredNorm() / static_cast<double>(raw.size()));
    s.max_mm = raw.cwiseAbs().maxCoeff();
  }
  return s;
}

Result<IdentificationResult> identify(const Mechanism& nominal, const MeasurementSet& data,
                                      const IdentifyOptions& options) {
  auto layout = parameter_layout(nominal);
  if (!layout) return layout.error();
  auto residuals = ResidualModel::make(nominal, data, options.residuals);
  if (!residuals) return residuals.error();
  const int n = layout->size();
  if (residuals->rows() < n) {
    return make_error(
        ErrorCode::bad_input,
        fmt::format("{} measured poses give {} equations for {} parameters: measure at least as many "
                    "equations as parameters (more, for a least-squares fit)",
                    data.poses.size(), residuals->rows(), n));
  }
  IdentificationResult result;
  result.layout = *layout;
  result.nominal = parameter_vector(layout->groups);

  // What the plan can identify is judged at the commanded poses (ResidualModel::at_commanded_poses), so that
  // noise cannot lend a degenerate plan directions it does not have.
  const ResidualModel design = residuals->at_commanded_poses();
  std::vector<Pose> poses = residuals->start_poses();
  Eigen::VectorXd raw, weighted;
  if (auto ok = residuals_at(*residuals, nominal, *layout, result.nominal, poses, raw, weighted); !ok) {
    return ok.error();
  }
  result.before = summarize_residuals(weighted, raw);
  auto start_jacobian = residual_jacobian(design, nominal, *layout, result.nominal, poses);
  if (!start_jacobian) return start_jacobian.error();
  result.at_start = analyse_identifiability(*start_jacobian, *layout, options.identifiability);
  result.warnings = result.at_start.warnings;
  const Eigen::MatrixXd basis = result.at_start.identifiable_basis();
  for (int i = 0; i < n; ++i) {
    if (basis.row(i).norm() < 1e-9)
      result.unchanged_parameters.push_back(layout->names[static_cast<std::size_t>(i)]);
  }

  Eigen::LevenbergMarquardtSpace::Status status = Eigen::LevenbergMarquardtSpace::ImproperInputParameters;
  Eigen::VectorXd z = Eigen::VectorXd::Zero(result.at_start.rank);
  SubspaceProblem problem(*residuals, nominal, *layout, result.nominal, basis);
  if (result.at_start.rank > 0) {
    Eigen::LevenbergMarquardt<SubspaceProblem> solver(problem);
    solver.setMaxfev(options.max_evaluations);
    solver.setFtol(options.relative_reduction_tolerance);
    solver.setXtol(options.relative_step_tolerance);
    solver.setFactor(options.initial_step_bound);
    status = solver.minimize(z);
    result.iterations = static_cast<int>(solver.iterations()) - 1;  // MINPACK counts from 1
    if (problem.failure) return *problem.failure;
  }
  result.evaluations = problem.evaluations;
  result.jacobians = problem.jacobians;
  const bool converged = solver_converged(status);
  result.solver_message =
      result.at_start.rank > 0 ? solver_text(status) : "no parameter combination is identifiable";
  result.identified = problem.parameters(z);

  poses = problem.poses;
  if (auto ok = residuals_at(*residuals, nominal, *layout, result.identified, poses, raw, weighted); !ok) {
    return ok.error();
  }
  result.after = summarize_residuals(weighted, raw);
  auto final_jacobian = residual_jacobian(design, nominal, *layout, result.identified, poses);
  if (!final_jacobian) return final_jacobian.error();
  result.at_solution = analyse_identifiability(*final_jacobian, *layout, options.identifiability);
  const int dof = residuals->rows() - result.at_start.rank;
  result.variance_factor = dof > 0 ? weighted.squaredNorm() / dof : 0.0;

  result.groups = groups_from_vector(*layout, result.identified);
  auto mechanism = nominal.with_geometry(result.groups);
  if (!mechanism) return mechanism.error();
  result.mechanism = std::move(*mechanism);

  if (!converged) {
    result.status = IdentificationStatus::not_converged;
    result.warnings.push_back(
        fmt::format("the solver stopped without converging: {}", result.solver_message));
  } else {
    result.status = result.at_start.full_rank() ? IdentificationStatus::identified
                                                : IdentificationStatus::partially_identified;
  }
  return result;
}

}  // namespace pkm::calibration
