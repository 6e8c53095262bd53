#pragma once
// What the machine file's `stiffness:` section says about the elastic parts that carry a cutting load
// (docs/machine-file.md, docs/stiffness.md; Rusanov et al.): the struts (an axial stiffness
// c_j, or a modulus and a section whose stiffness E·A/L follows the strut's length), the joints at their
// ends, the carriage drives and guides of glide machines, and an optional frame of beams.
#include <array>

#include "machine/frame_parameters.hpp"
#include "machine/mechanism.hpp"

namespace pkm {

struct StrutStiffness {
  double stiffness_N_mm = 0.0;  ///< c_j, when given as such
  double modulus_N_mm2 = 0.0;   ///< E, with area_mm2: c = E·A/L at the strut's length L
  double area_mm2 = 0.0;
  /// c at the strut length `length_mm` (mm between its joints), N/mm.
  double at_length(double length_mm) const {
    return area_mm2 > 0.0 ? modulus_N_mm2 * area_mm2 / length_mm : stiffness_N_mm;
  }
};

/// The compliance of the joints at a strut's two ends (Rusanov et al., "Joint": Δ − u = K_u·Q,
/// φ − θ = K_θ·M; printed K_u·M, corrected: the displacement follows the force Q, not the moment). A
/// spherical or cardan joint passes no moment about its free axes, so along a pin-jointed strut only the
/// translational compliance along the strut's line acts: the strut's own spring in series with u_jᵀ K_u u_j
/// at each end. Isotropic here (K_u = compliance · I); 0 is a rigid ("frozen") joint.
struct JointCompliance {
  double base_mm_N = 0.0;           ///< K_u of the base-side joint (the carriage's, on glide machines)
  double platform_mm_N = 0.0;       ///< K_u of the platform joint
  double rotational_rad_Nmm = 0.0;  ///< K_θ: read and kept; no moment crosses a pin-jointed strut's ends
};

/// Glide machines: the carriage of strut j is held along its guide by its drive (stiffness k_d along the
/// guide direction e_j) and across it by the guide (compliance C_g, isotropic here). A strut force f along
/// the strut's unit line n moves the carriage by (n·e) f / k_d along e and by C_g f across, so the strut's
/// end gives way by f ((n·e)² / k_d + nᵀ C_g n) along its line: in series with the strut (1/k_a +
/// (n·e)²/k_d + nᵀ C_g n).
struct CarriageCompliance {
  double drive_stiffness_N_mm = 0.0;  ///< k_d; 0: a rigid drive
  double guide_mm_N = 0.0;            ///< C_g; 0: a rigid guide
};

/// Which elastic parts a compliance counts (the models, from the simplest to the full one).
enum class StiffnessModel {
  struts,         ///< the struts only: K = Gᵀ diag(k) G
  struts_joints,  ///< with the joints, and with the carriage drives and guides of glide machines
  frame,          ///< with the frame of beams as well (a finite-element model)
};

struct StiffnessParameters {
  int strut_count = 0;
  std::array<StrutStiffness, kMaxActuators> struts{};
  std::array<JointCompliance, kMaxActuators> joints{};
  std::array<CarriageCompliance, kMaxActuators> carriages{};
  FrameParameters frame;  ///< empty: the base is rigid
  /// The model the file asks for (`model:`); by default the fullest the file describes.
  StiffnessModel model = StiffnessModel::struts;
  int line = 0;  ///< line of `stiffness:` in the machine file (0: not given)
  bool given() const { return line > 0; }
};

}  // namespace pkm
