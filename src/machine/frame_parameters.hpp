#pragma once
// The machine frame of the `stiffness:` section (Rusanov et al.'s FE model,
// docs/stiffness_frame.md): beams between nodes that carry the struts' base joints, the platform being a
// rigid master node of the finite-element model. Empty when the base is rigid.
//
// A beam's own axes (Rusanov's cantilever frame): z along the beam from its first node to its second, x and
// y the section's principal axes, x the part of `section_x` square to z, y = z × x. second_moment_x_mm4 (J_x)
// resists bending in the y-z plane (deflection along y), second_moment_y_mm4 (J_y) bending in the x-z plane
// (deflection along x): second moments of area (∫ y² dA, ∫ x² dA), not the printed static moments.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace pkm {

struct FrameNode {
  std::string name;
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();  ///< base frame
  bool fixed = false;                                     ///< clamped: all six motions held (a support)
  int line = 0;                                           ///< of the node's entry in the machine file
};

/// A beam's section and material (the same for its whole length).
struct BeamSection {
  double modulus_N_mm2 = 0.0;         ///< E
  double shear_modulus_N_mm2 = 0.0;   ///< G
  double area_mm2 = 0.0;              ///< F
  double second_moment_x_mm4 = 0.0;   ///< J_x about the section's x axis
  double second_moment_y_mm4 = 0.0;   ///< J_y about the section's y axis
  double torsion_constant_mm4 = 0.0;  ///< J_t (Rusanov's J_r; the polar moment only for round sections)
};

struct FrameBeam {
  int from = 0;  ///< node index (FrameParameters::nodes)
  int to = 0;
  BeamSection section;
  /// A direction whose part square to the beam is the section's x axis (base frame, need not be unit).
  Eigen::Vector3d section_x = Eigen::Vector3d::UnitZ();
  int line = 0;  ///< of the beam's entry in the machine file
};

struct FrameParameters {
  std::vector<FrameNode> nodes;
  std::vector<FrameBeam> beams;
  /// The node that carries each strut's base joint (index into nodes, one per strut): the joint is rigidly
  /// offset from it, so it moves by u_n + θ_n × (A_j − x_n).
  std::vector<int> strut_nodes;
  std::string source;  ///< the machine file, for errors found when the model is built
  int line = 0;        ///< line of `stiffness.frame` in it (0: not from a file)
  bool empty() const { return nodes.empty(); }
};

}  // namespace pkm
