#include "stiffness/frame_structure.hpp"

#include <fmt/format.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <numeric>

namespace pkm::stiffness {
namespace {

// Union-find over the nodes, for which of them the beams join to a support.
int frame_root(std::vector<int>& parent, int n) {
  while (parent[n] != n) n = parent[n] = parent[parent[n]];
  return n;
}

// A pivot of L D Lᵀ below this fraction of its diagonal entry (the scale-free test: mm and rad DOF alike) is
// a motion nothing resists.
constexpr double kFramePivotRatio = 1e-12;

}  // namespace

FrameDofs number_frame_dofs(const FrameParameters& frame) {
  FrameDofs dofs;
  dofs.first.assign(frame.nodes.size(), -1);
  for (std::size_t n = 0; n < frame.nodes.size(); ++n) {
    if (frame.nodes[n].fixed) continue;
    dofs.first[n] = dofs.count;
    dofs.count += 6;
  }
  return dofs;
}

std::vector<Matrix12> frame_beam_stiffness(const FrameParameters& frame) {
  std::vector<Matrix12> out;
  out.reserve(frame.beams.size());
  for (const FrameBeam& beam : frame.beams) {
    out.push_back(beam_stiffness_global(beam.section, frame.nodes[beam.from].position_mm,
                                        frame.nodes[beam.to].position_mm, beam.section_x));
  }
  return out;
}

Error frame_mechanism_error(const FrameParameters& frame, const std::string& detail) {
  const std::string place = frame.line > 0 ? fmt::format("{}:{}: ", frame.source, frame.line)
                                           : (frame.source.empty() ? "" : frame.source + ": ");
  return Error{ErrorCode::singular,
               fmt::format("{}stiffness.frame: singular stiffness matrix: the frame is a mechanism: {}",
                           place, detail),
               ErrorLocation{frame.source, frame.line, 0, "stiffness.frame"}};
}

Status check_frame_supported(const FrameParameters& frame) {
  const int count = static_cast<int>(frame.nodes.size());
  std::vector<int> parent(count);
  std::iota(parent.begin(), parent.end(), 0);
  for (const FrameBeam& beam : frame.beams)
    parent[frame_root(parent, beam.from)] = frame_root(parent, beam.to);
  std::vector<bool> held(count, false);
  for (int n = 0; n < count; ++n) {
    if (frame.nodes[n].fixed) held[frame_root(parent, n)] = true;
  }
  for (int n = 0; n < count; ++n) {
    if (!held[frame_root(parent, n)]) {
      return frame_mechanism_error(
          frame,
          fmt::format("node '{}' (line {}) is not joined through beams to a fixed node, so it moves as a "
                      "rigid body (fix a node of its part)",
                      frame.nodes[n].name, frame.nodes[n].line));
    }
  }
  return ok_status();
}

Result<std::vector<Vector6>> frame_displacements(const FrameParameters& frame,
                                                 const std::vector<Vector6>& loads) {
  if (Status supported = check_frame_supported(frame); !supported) return supported.error();
  const FrameDofs dofs = number_frame_dofs(frame);
  const std::vector<Matrix12> beams = frame_beam_stiffness(frame);
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t b = 0; b < beams.size(); ++b) {
    const int ends[2] = {dofs.first[frame.beams[b].from], dofs.first[frame.beams[b].to]};
    for (int i = 0; i < 12; ++i) {
      for (int j = 0; j < 12; ++j) {
        if (ends[i / 6] < 0 || ends[j / 6] < 0) continue;
        entries.emplace_back(ends[i / 6] + i % 6, ends[j / 6] + j % 6, beams[b](i, j));
      }
    }
  }
  Eigen::SparseMatrix<double> k(dofs.count, dofs.count);
  k.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(dofs.count);
  for (std::size_t n = 0; n < frame.nodes.size(); ++n) {
    if (dofs.first[n] >= 0) rhs.segment<6>(dofs.first[n]) = loads[n];
  }
  std::vector<Vector6> out(frame.nodes.size(), Vector6::Zero());
  if (dofs.count == 0) return out;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor(k);
  // The pivots in the factor's order against the diagonal in the same order.
  const Eigen::VectorXd diagonal = factor.permutationP() * Eigen::VectorXd(k.diagonal());
  if (factor.info() != Eigen::Success ||
      !((factor.vectorD().array() > kFramePivotRatio * diagonal.array()).all())) {
    return frame_mechanism_error(frame, "some motion of the frame deforms no beam");
  }
  const Eigen::VectorXd x = factor.solve(rhs);
  for (std::size_t n = 0; n < frame.nodes.size(); ++n) {
    if (dofs.first[n] >= 0) out[n] = x.segment<6>(dofs.first[n]);
  }
  return out;
}

}  // namespace pkm::stiffness
