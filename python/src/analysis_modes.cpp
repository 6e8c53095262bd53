// pkm.modes: the natural frequencies and mode shapes of the elastic struts at a pose, as `pkm modes --pose`
// (pipeline/modes_job.hpp, the same job): the drives clamped, about the static equilibrium under gravity.
#include "analysis_bindings.hpp"
#include "bindings.hpp"
#include "pipeline/modes_job.hpp"
#include "pipeline_support.hpp"

namespace pkm::python {

namespace {

template <class Vector>
py::array_t<double> numpy_vector(const Vector& v, int count) {
  return numpy_from(std::vector<double>(v.data(), v.data() + count));
}

}  // namespace

void bind_modes(py::module_& m) {
  m.def(
      "modes",
      [](const Machine& machine, const py::object& pose_value) {
        const Mechanism& mechanism = *machine.mechanism;
        const Pose pose = pose_from_python(mechanism, pose_value, "pose");
        const pipeline::ModesJobResult r = unwrap_released([&] {
          return pipeline::run_modes_job(machine, {pose, {}});
        });
        const dynamics::NaturalModes& modes = r.modes;
        py::dict out;
        out["pose"] = numpy_pose(mechanism, pose);
        out["frequencies_Hz"] = numpy_vector(modes.frequency_Hz, modes.count);
        out["shapes"] = numpy_matrix(modes.shape);
        out["coordinates"] = py::cast(r.coordinates);
        out["mass"] = numpy_matrix(modes.mass);
        out["stiffness"] = numpy_matrix(modes.stiffness);
        out["static_deflection_mm"] = numpy_vector(r.static_deflection_mm, 3);
        out["static_rotation_deg"] = r.static_rotation_deg;
        out["equilibrium_pose"] = numpy_pose(mechanism, modes.equilibrium.pose);
        out["strut_tension_N"] = numpy_vector(modes.equilibrium.strut_force_N,
                                              static_cast<int>(modes.equilibrium.strut_force_N.size()));
        out["geometric_stiffness_share"] = modes.geometric_share;
        return out;
      },
      py::arg("machine"), py::arg("pose"),
      R"doc(Natural frequencies and mode shapes of the machine's elastic struts at `pose`, as `pkm modes --pose`.

pose: [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] in the machine's angle convention. The drives are clamped at the
pose's actuator values and the platform rests at its static equilibrium under gravity (the machine file's
dynamics: section with stiffness_N_mm for every strut).

Returns a dict: frequencies_Hz (m,) ascending; shapes (m, m): column i is mode i in the basis coordinates
named by coordinates (x_mm ... rz_rad: twist of the platform about the tool point, base frame), scaled to a
largest platform-joint motion of 1 mm; mass (m, m) M and stiffness (m, m) K in the
same coordinates (kg and kg/s², i.e. N/mm × 10³, for mm; kg·mm² for rad), so that K v = ω² M v for each mode; static_deflection_mm (3,) and static_rotation_deg of the equilibrium from the pose; equilibrium_pose;
strut_tension_N (n,); geometric_stiffness_share; pose (the completed pose).
Raises pkm.InputError (key 'dynamics') for a machine without the model, pkm.UnreachableError /
pkm.LimitExceededError for a pose out of reach.)doc");
}

}  // namespace pkm::python
