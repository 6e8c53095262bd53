#pragma once
// Readers of the machine-file sections every mechanism shares, beside the top-level keys that
// machine_file.cpp reads itself: `limits:`, `motion:`, `masses:`, `dynamics:`, `drives:` and the
// passive-joint neutral axes. Each error names the file, the line and the key (docs/machine-file.md).
#include <yaml-cpp/yaml.h>

#include "io/yaml_reader.hpp"
#include "machine/machine.hpp"

namespace pkm {

/// Everything `limits:` holds. Actuator values as written (mm or deg); joint angles already in rad.
struct FileLimits {
  ActuatorLimits actuators;
  JointLimits joints;
};

/// `limits:` (optional, every key optional). Planar machines have pin joints without a swing limit: the two
/// joint-angle keys are rejected there.
Result<FileLimits> read_limits(const YAML::Node& root, const YamlReader& reader, bool planar);

/// `motion:` (optional, every key optional, defaults as in MotionSettings). Planar machines give
/// program_origin_mm as [x, y] or [x, y, 0].
Result<MotionSettings> read_motion_settings(const YAML::Node& root, const YamlReader& reader, bool planar);

/// `drives:` (optional, every key optional): the resolution (`step_mm`, or `step_deg` when the actuators are
/// angles), the largest step rate and the servo period, all positive, the period within 0.1…20 ms.
Result<DriveSettings> read_drive_settings(const YAML::Node& root, const YamlReader& reader,
                                          bool angular_actuators);

/// `masses:` (optional, every key optional, defaults as in MassProperties): masses must not be negative,
/// vectors have three numbers (planar machines may give platform_com_mm as [x, y]).
Result<MassProperties> read_mass_properties(const YAML::Node& root, const YamlReader& reader, bool planar);

/// `dynamics:` (optional; docs/machine-file.md): `platform:` with its mass required, the payload, the struts
/// (one mapping for all, or one per actuator of `mechanism`), gravity and the drive model. Masses ≥ 0,
/// inertia tensors those of a real body (positive semi-definite, principal moments within the triangle
/// inequality), stiffness > 0, friction coefficients ≥ 0, lag τ > 0. Inertias are read in kg·m² and kept in
/// kg·mm². Planar machines may give centres of mass as [x, y]. Glide machines and rotopods (constant-length
/// struts) have no `upper` strut part; only they may give `carriage_kg` > 0.
Result<DynamicsParameters> read_dynamics(const YAML::Node& root, const YamlReader& reader,
                                         const Mechanism& mechanism, bool planar);

/// `stiffness:` (optional; docs/machine-file.md): `struts:` as one mapping for every strut or a list of one
/// per actuator, each with `stiffness_N_mm` > 0, or `modulus_N_mm2` and `area_mm2` > 0 (E·A/L).
Result<StiffnessParameters> read_stiffness(const YAML::Node& root, const YamlReader& reader,
                                           const Mechanism& mechanism);

/// `servo:` (optional; docs/machine-file.md): the tuning (technical_optimum, symmetric_optimum or explicit),
/// the drives' loop period (> 0, ≤ 20 ms; not given: the servo period), the velocity feedforward (0…1) and
/// `drives:` as one mapping for every drive or a list of one per actuator of `mechanism`: the current loop's
/// time constant, the base speed and force, the motor inertia with the screw's lead (or gear ratio), the
/// clamps, and the gains with tuning: explicit only (required there, refused otherwise). The unit keys follow
/// the actuators' kind (mm, mm/s, N; angular actuators deg, deg/s, N·mm, kept in rad); the other kind's key
/// is an error naming the one to give. Every number finite, unknown keys refused.
Result<ServoParameters> read_servo(const YAML::Node& root, const YamlReader& reader,
                                   const Mechanism& mechanism);

/// `stiffness.frame` (optional; docs/stiffness_frame.md) of the mapping `stiffness`: named `sections`,
/// `nodes` (name, position_mm, fixed), `beams` (from, to, section name or mapping, section_x) and
/// `base_joint_nodes` (one node name per strut). Moduli and section constants > 0, node names unique and
/// known, beams of non-zero length with section_x not along them; unknown keys refused.
Result<FrameParameters> read_frame(const YAML::Node& stiffness, const YamlReader& reader, int strut_count);

/// The neutral axes of the mechanism's passive joints: `base_joint_axes` / `platform_joint_axes` if given,
/// otherwise the strut directions at the mechanism's home. Errors if a key is given for a mechanism without
/// swing joints, or a given axis has zero length.
Result<PassiveJointAxes> read_passive_joint_axes(const YAML::Node& root, const YamlReader& reader,
                                                 const Mechanism& mechanism);

}  // namespace pkm
