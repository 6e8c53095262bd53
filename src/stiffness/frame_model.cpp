#include "stiffness/frame_model.hpp"

#include <fmt/format.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>

namespace pkm::stiffness {
namespace {

using SparseUpper = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// A pivot of L D Lᵀ below this fraction of its diagonal entry (the pivots of the matrix equilibrated to a
// unit diagonal, so mm and rad unknowns weigh alike, as strut_compliance's test) is a motion nothing holds.
constexpr double kFrameUnboundedRatio = 1e-12;

// The largest strut's unknowns: its frame node's six and the platform's six.
constexpr int kMaxStrutUnknowns = 12;

using PlatformMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using PlatformVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;
using StrutVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxStrutUnknowns, 1>;

// Index of entry (row, col) of an upper-triangular compressed column matrix in its values.
int value_index(const SparseUpper& k, int row, int col) {
  const int* begin = k.innerIndexPtr() + k.outerIndexPtr()[col];
  const int* end = k.innerIndexPtr() + k.outerIndexPtr()[col + 1];
  const int* at = std::lower_bound(begin, end, row);
  return static_cast<int>(at - k.innerIndexPtr());
}

// The position of every unknown in the elimination order: the frame's unknowns (the first `frame_unknowns`)
// in approximate minimum-degree order of the whole pattern, the platform's last. Then the factor's trailing m
// × m block is the platform's Schur complement, L_pp D_p L_ppᵀ = ((K⁻¹)_pp)⁻¹, and the compliance needs no
// solve. (The platform couples to every strut's node, so minimum degree puts it near the end anyway.)
std::vector<int> platform_last_order(const SparseUpper& pattern, int frame_unknowns) {
  const int n = static_cast<int>(pattern.rows());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> by_degree;
  Eigen::AMDOrdering<int>()(pattern, by_degree);  // position → unknown
  std::vector<int> order(n, 0);
  int next = 0;
  for (int position = 0; position < n; ++position) {
    const int unknown = by_degree.indices()[position];
    if (unknown < frame_unknowns) order[unknown] = next++;
  }
  for (int unknown = frame_unknowns; unknown < n; ++unknown) order[unknown] = unknown;
  return order;
}

}  // namespace

struct FrameModel::Impl {
  // Eigen's SimplicialLDLT::factorize() builds a temporary matrix on every call, even when no permutation is
  // left to apply. The matrix here is assembled already in the minimum-degree order and analysed once with
  // the natural order, so its numeric factorisation can run on it in place, without allocating.
  class PreorderedLdlt
      : public Eigen::SimplicialLDLT<SparseUpper, Eigen::Upper, Eigen::NaturalOrdering<int>> {
   public:
    void factorize_in_place(const SparseUpper& matrix) { this->template factorize_preordered<true>(matrix); }
  };

  // Where strut j's bar adds to the matrix: its unknowns (the node's six in the original numbering, if the
  // node moves, then the platform's) and, for every pair a ≤ b of them, the place of its entry in the values.
  struct StrutSlots {
    int node = -1;      ///< frame node carrying the base joint; −1: on the ground
    int node_dof = -1;  ///< its first unknown, −1 when it does not move
    int unknowns = 0;   ///< 6 + m, or m
    std::array<int, kMaxStrutUnknowns * kMaxStrutUnknowns> value_at{};  ///< [a * 12 + b], a ≤ b
  };

  const Mechanism* mechanism = nullptr;
  StiffnessParameters stiffness;
  FrameDofs frame_dofs;
  int platform_unknowns = 0;         ///< m: the platform twists the mechanism allows
  int unknowns = 0;                  ///< n = frame DOF + m
  std::vector<int> order;            ///< minimum-degree position of every unknown
  SparseUpper k;                     ///< upper triangle, in that order
  std::vector<double> frame_values;  ///< the beams' part of k's values (constant)
  std::vector<int> diagonal_at;      ///< value index of each diagonal entry
  std::vector<StrutSlots> struts;
  bool carriages_move = false;  ///< some carriage's drive or guide gives way (series_compliance_mm_N)
  PreorderedLdlt factor;
  // Per-pose state and buffers, sized at construction.
  StrutJointPoints ends;
  TwistBasis allowed;
  std::array<StrutVector, kMaxActuators> strut_line;  ///< g_j over its unknowns
  ActuatorVector strut_stiffness;
  Eigen::VectorXd load, solution;  ///< n

  int platform_position(int a) const { return order[frame_dofs.count + a]; }
  Status assemble(const Pose& pose, ToolCompliance& out);
};

namespace {

// A bar for every strut, a base-joint node for every strut, and a frame that is held.
Status check_frame_fits(const Mechanism& mechanism, const StiffnessParameters& stiffness) {
  const FrameParameters& frame = stiffness.frame;
  const int strut_count = stiffness.strut_count;
  StrutJointPoints home_ends;
  const int home_struts = mechanism.strut_ends(mechanism.home(), home_ends);
  if (strut_count <= 0 || strut_count != mechanism.actuator_count() || home_struts != strut_count) {
    return make_error(ErrorCode::unsupported,
                      fmt::format("the frame model needs a bar for every strut: the {} has {} struts, the "
                                  "stiffness parameters {}",
                                  to_string(mechanism.type()), home_struts, strut_count));
  }
  if (!frame.empty() && static_cast<int>(frame.strut_nodes.size()) != strut_count) {
    return make_error(ErrorCode::bad_input, fmt::format("stiffness.frame: {} base-joint nodes for {} struts",
                                                        frame.strut_nodes.size(), strut_count));
  }
  return check_frame_supported(frame);
}

}  // namespace

FrameModel::FrameModel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FrameModel::FrameModel(FrameModel&&) noexcept = default;
FrameModel& FrameModel::operator=(FrameModel&&) noexcept = default;
FrameModel::~FrameModel() = default;

Result<FrameModel> FrameModel::make(const Mechanism& mechanism, const StiffnessParameters& stiffness) {
  auto impl = std::make_unique<Impl>();
  impl->mechanism = &mechanism;
  impl->stiffness = stiffness;
  const FrameParameters& frame = stiffness.frame;
  const int strut_count = stiffness.strut_count;
  if (Status fits = check_frame_fits(mechanism, stiffness); !fits) return fits.error();

  impl->frame_dofs = number_frame_dofs(frame);
  const int frame_unknowns = impl->frame_dofs.count;
  const int m = mechanism.controlled_axes().count();
  impl->platform_unknowns = m;
  const int n = frame_unknowns + m;
  impl->unknowns = n;

  // Every strut's unknowns in the original numbering: node (if it moves), then the platform's.
  impl->struts.resize(strut_count);
  const auto strut_unknowns = [&](const Impl::StrutSlots& s, int a) {
    return s.node_dof >= 0 ? (a < 6 ? s.node_dof + a : frame_unknowns + a - 6) : frame_unknowns + a;
  };
  for (int j = 0; j < strut_count; ++j) {
    Impl::StrutSlots& s = impl->struts[j];
    s.node = frame.empty() ? -1 : frame.strut_nodes[j];
    s.node_dof = s.node >= 0 ? impl->frame_dofs.first[s.node] : -1;
    s.unknowns = (s.node_dof >= 0 ? 6 : 0) + m;
  }

  // The pattern of the whole symmetric matrix, for the minimum-degree order.
  const std::vector<Matrix12> beams = frame_beam_stiffness(frame);
  const auto beam_unknown = [&](const FrameBeam& beam, int i) {
    const int first = impl->frame_dofs.first[i < 6 ? beam.from : beam.to];
    return first < 0 ? -1 : first + i % 6;
  };
  std::vector<Eigen::Triplet<double>> pattern;
  for (const FrameBeam& beam : frame.beams) {
    for (int i = 0; i < 12; ++i) {
      for (int j = 0; j < 12; ++j) {
        const int r = beam_unknown(beam, i), c = beam_unknown(beam, j);
        if (r >= 0 && c >= 0) pattern.emplace_back(r, c, 1.0);
      }
    }
  }
  for (const Impl::StrutSlots& s : impl->struts) {
    for (int a = 0; a < s.unknowns; ++a) {
      for (int b = 0; b < s.unknowns; ++b)
        pattern.emplace_back(strut_unknowns(s, a), strut_unknowns(s, b), 1.0);
    }
  }
  SparseUpper full(n, n);
  full.setFromTriplets(pattern.begin(), pattern.end());
  impl->order = platform_last_order(full, frame_unknowns);

  // The upper triangle in that order: the beams' values, and explicit zeros where the struts will add.
  const std::vector<int>& at = impl->order;
  std::vector<Eigen::Triplet<double>> upper;
  for (std::size_t b = 0; b < beams.size(); ++b) {
    for (int i = 0; i < 12; ++i) {
      for (int j = 0; j < 12; ++j) {
        const int r = beam_unknown(frame.beams[b], i), c = beam_unknown(frame.beams[b], j);
        if (r >= 0 && c >= 0 && at[r] <= at[c]) upper.emplace_back(at[r], at[c], beams[b](i, j));
      }
    }
  }
  for (const Impl::StrutSlots& s : impl->struts) {
    for (int a = 0; a < s.unknowns; ++a) {
      for (int b = 0; b < s.unknowns; ++b) {
        const int r = at[strut_unknowns(s, a)], c = at[strut_unknowns(s, b)];
        if (r <= c) upper.emplace_back(r, c, 0.0);
      }
    }
  }
  impl->k.resize(n, n);
  impl->k.setFromTriplets(upper.begin(), upper.end());
  impl->k.makeCompressed();
  impl->frame_values.assign(impl->k.valuePtr(), impl->k.valuePtr() + impl->k.nonZeros());
  impl->diagonal_at.resize(n);
  for (int i = 0; i < n; ++i) impl->diagonal_at[i] = value_index(impl->k, i, i);
  for (Impl::StrutSlots& s : impl->struts) {
    for (int a = 0; a < s.unknowns; ++a) {
      for (int b = a; b < s.unknowns; ++b) {
        const int r = at[strut_unknowns(s, a)], c = at[strut_unknowns(s, b)];
        s.value_at[a * kMaxStrutUnknowns + b] = value_index(impl->k, std::min(r, c), std::max(r, c));
      }
    }
  }
  impl->factor.analyzePattern(impl->k);
  if (impl->factor.info() != Eigen::Success)
    return make_error(ErrorCode::singular, "the frame model's stiffness pattern could not be analysed");

  for (int j = 0; j < strut_count && stiffness.model != StiffnessModel::struts; ++j) {
    const CarriageCompliance& c = stiffness.carriages[j];
    impl->carriages_move = impl->carriages_move || c.drive_stiffness_N_mm > 0.0 || c.guide_mm_N > 0.0;
  }
  impl->strut_stiffness.resize(strut_count);
  for (int j = 0; j < strut_count; ++j) impl->strut_line[j].resize(impl->struts[j].unknowns);
  impl->load = Eigen::VectorXd::Zero(n);
  impl->solution = Eigen::VectorXd::Zero(n);
  impl->allowed = TwistBasis::Identity(6, m);
  return FrameModel(std::move(impl));
}

// Fills k with the beams and the struts at `pose` and factorises it; `out` gets the pose and the struts.
Status FrameModel::Impl::assemble(const Pose& pose, ToolCompliance& out) {
  auto completed = mechanism->complete_pose(pose);
  if (!completed) return completed.error();
  out.pose = *completed;
  const int strut_count = stiffness.strut_count;
  if (mechanism->strut_ends(out.pose, ends) != strut_count)
    return make_error(ErrorCode::unreachable, "the pose is out of the mechanism's reach");
  const int m = platform_unknowns;
  out.dof = m;
  // A mechanism that controls all six coordinates allows every twist: no projection (as strut_compliance).
  if (m < 6 && !mechanism->controlled_twists(out.pose, allowed))
    return make_error(ErrorCode::singular, "the mechanism's constraints are singular at this pose");
  // The carriages' positions, for their drives and guides in series with the struts (glide machines).
  std::array<double, kMaxActuators> actuators{};
  if (carriages_move && !mechanism->actuator_values(out.pose, actuators.data()))
    return make_error(ErrorCode::unreachable, "the pose is out of the mechanism's reach");

  std::copy(frame_values.begin(), frame_values.end(), k.valuePtr());
  double* values = k.valuePtr();
  out.strut_lines.resize(strut_count, 6);
  out.strut_stiffness_N_mm.resize(strut_count);
  out.strut_length_mm.resize(strut_count);
  for (int j = 0; j < strut_count; ++j) {
    const StrutSlots& s = struts[j];
    const Eigen::Vector3d d = ends.platform_mm[j] - ends.base_mm[j];
    const double length = d.norm();
    if (!(length > 0.0))
      return make_error(ErrorCode::singular, fmt::format("strut {} has zero length", j + 1));
    const Eigen::Vector3d u = d / length;
    Eigen::Vector3d carriage_motion = Eigen::Vector3d::Zero(), unused;
    if (carriages_move) mechanism->base_joint_motion(j, actuators[j], carriage_motion, unused);
    const double c = 1.0 / (1.0 / stiffness.struts[j].at_length(length) +
                            series_compliance_mm_N(stiffness, j, u, carriage_motion));
    Vector6 platform_line;
    platform_line << u, (ends.platform_mm[j] - out.pose.position_mm).cross(u);
    out.strut_lines.row(j) = platform_line.transpose();
    out.strut_length_mm[j] = length;
    out.strut_stiffness_N_mm[j] = c;
    strut_stiffness[j] = c;
    // The stretch g_jᵀ x: the platform joint moves by d + θ × (B_j − p), the base joint by
    // u_n + θ_n × (A_j − x_n), along u.
    StrutVector& g = strut_line[j];
    int p = 0;
    if (s.node_dof >= 0) {
      const Eigen::Vector3d offset = ends.base_mm[j] - stiffness.frame.nodes[s.node].position_mm;
      g.head<3>() = -u;
      g.segment<3>(3) = -offset.cross(u);
      p = 6;
    }
    if (m == 6) {
      g.segment<6>(p) = platform_line;
    } else {
      g.segment(p, m) = allowed.transpose() * platform_line;
    }
    for (int a = 0; a < s.unknowns; ++a) {
      const double cga = c * g[a];
      for (int b = a; b < s.unknowns; ++b) values[s.value_at[a * kMaxStrutUnknowns + b]] += cga * g[b];
    }
  }
  factor.factorize_in_place(k);
  bool held = factor.info() == Eigen::Success;
  const auto pivots = factor.vectorD();
  for (int i = 0; held && i < unknowns; ++i) held = pivots[i] > kFrameUnboundedRatio * values[diagonal_at[i]];
  if (!held) {
    return make_error(
        ErrorCode::singular,
        "unbounded compliance: the struts and the frame cannot hold the platform in some direction "
        "here (a singular position)");
  }
  return ok_status();
}

Result<ToolCompliance> FrameModel::compliance(const Pose& pose) {
  Impl& s = *impl_;
  ToolCompliance out;
  if (Status assembled = s.assemble(pose, out); !assembled) return assembled.error();
  // (K⁻¹)_pp = (L_pp D_p L_ppᵀ)⁻¹ = L_pp⁻ᵀ D_p⁻¹ L_pp⁻¹ from the factor's last m columns (unit lower L_pp).
  const int m = s.platform_unknowns;
  const int first = s.unknowns - m;
  const SparseUpper& l = s.factor.matrixL().nestedExpression();
  PlatformMatrix l_pp = PlatformMatrix::Identity(m, m);
  for (int c = 0; c < m; ++c) {
    for (SparseUpper::InnerIterator it(l, first + c); it; ++it) l_pp(it.row() - first, c) = it.value();
  }
  const PlatformMatrix l_inverse =
      l_pp.triangularView<Eigen::UnitLower>().solve(PlatformMatrix::Identity(m, m));
  const PlatformMatrix platform =
      l_inverse.transpose() * s.factor.vectorD().tail(m).cwiseInverse().asDiagonal() * l_inverse;
  if (m == 6) {
    out.compliance = platform;
  } else {
    out.compliance = s.allowed * platform * s.allowed.transpose();
  }
  out.compliance = 0.5 * (out.compliance + out.compliance.transpose()).eval();
  return out;
}

Status FrameModel::deflection(const Pose& pose, const statics::Wrench& load, FrameDeflection& out) {
  Impl& s = *impl_;
  ToolCompliance at;
  if (Status assembled = s.assemble(pose, at); !assembled) return assembled;
  const int m = s.platform_unknowns;
  Vector6 wrench;
  wrench << load.force_N, load.moment_Nmm;
  PlatformVector generalised(m);
  if (m == 6) {
    generalised = wrench;
  } else {
    generalised = s.allowed.transpose() * wrench;
  }
  s.load.setZero();
  for (int a = 0; a < m; ++a) s.load[s.platform_position(a)] = generalised[a];
  s.solution = s.factor.solve(s.load);
  PlatformVector q(m);
  for (int a = 0; a < m; ++a) q[a] = s.solution[s.platform_position(a)];
  if (m == 6) {
    out.tool = q;
  } else {
    out.tool = s.allowed * q;
  }
  const FrameParameters& frame = s.stiffness.frame;
  out.node_displacement.resize(frame.nodes.size());
  for (std::size_t node = 0; node < frame.nodes.size(); ++node) {
    const int first = s.frame_dofs.first[node];
    for (int i = 0; i < 6; ++i)
      out.node_displacement[node][i] = first < 0 ? 0.0 : s.solution[s.order[first + i]];
  }
  const int strut_count = s.stiffness.strut_count;
  out.strut_tension_N.resize(strut_count);
  for (int j = 0; j < strut_count; ++j) {
    const Impl::StrutSlots& slots = s.struts[j];
    double stretch = 0.0;
    for (int a = 0; a < slots.unknowns; ++a) {
      const int unknown = slots.node_dof >= 0 ? (a < 6 ? slots.node_dof + a : s.frame_dofs.count + a - 6)
                                              : s.frame_dofs.count + a;
      stretch += s.strut_line[j][a] * s.solution[s.order[unknown]];
    }
    out.strut_tension_N[j] = s.strut_stiffness[j] * stretch;
  }
  return ok_status();
}

FrameDeflection FrameModel::make_deflection() const {
  FrameDeflection out;
  out.strut_tension_N = ActuatorVector::Zero(impl_->stiffness.strut_count);
  out.node_displacement.assign(impl_->stiffness.frame.nodes.size(), Vector6::Zero());
  return out;
}

int FrameModel::unknowns() const {
  return impl_->unknowns;
}

long FrameModel::factor_nonzeros() const {
  return static_cast<long>(impl_->factor.matrixL().nestedExpression().nonZeros());
}

}  // namespace pkm::stiffness
