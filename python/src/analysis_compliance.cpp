// pkm.compliance: the tool's compliance at a pose with the struts as the springs, as `pkm compliance --pose`
// (pipeline/compliance_job.hpp, the same job): the 6 × 6 matrix about the tool point and the principal
// stiffness.
#include "analysis_bindings.hpp"
#include "bindings.hpp"
#include "pipeline/compliance_job.hpp"
#include "pipeline_support.hpp"

namespace pkm::python {

namespace {

// N/mm → N/µm and N·mm/rad → N·m/mrad, the units `pkm compliance` prints.
constexpr double kNPerUmPerNPerMm = 1e-3, kNmPerMradPerNmmPerRad = 1e-6;

}  // namespace

void bind_compliance(py::module_& m) {
  m.def(
      "compliance",
      [](const Machine& machine, const py::object& pose_value) {
        const Mechanism& mechanism = *machine.mechanism;
        const Pose pose = pose_from_python(mechanism, pose_value, "pose");
        pipeline::ComplianceJob job;
        job.pose = pose;
        const pipeline::ComplianceJobResult r =
            unwrap_released([&] { return pipeline::run_compliance_job(machine, job); });
        const stiffness::ToolCompliance& c = r.compliance;
        const auto translation = stiffness::principal_stiffness(c, false);
        const auto rotation = stiffness::principal_stiffness(c, true);
        const auto n = static_cast<int>(c.strut_stiffness_N_mm.size());
        py::dict out;
        out["pose"] = numpy_pose(mechanism, c.pose);
        out["compliance"] = numpy_matrix(c.compliance);
        out["dof"] = c.dof;
        out["translational_stiffness_N_um"] =
            numpy_matrix(translation.stiffness, kNPerUmPerNPerMm).attr("ravel")();
        out["translational_directions"] = numpy_matrix(translation.directions);
        out["rotational_stiffness_Nm_mrad"] =
            numpy_matrix(rotation.stiffness, kNmPerMradPerNmmPerRad).attr("ravel")();
        out["rotational_axes"] = numpy_matrix(rotation.directions);
        out["strut_stiffness_N_mm"] =
            numpy_from(std::vector<double>(c.strut_stiffness_N_mm.data(), c.strut_stiffness_N_mm.data() + n));
        out["strut_length_mm"] =
            numpy_from(std::vector<double>(c.strut_length_mm.data(), c.strut_length_mm.data() + n));
        out["strut_lines"] = numpy_matrix(c.strut_lines);
        return out;
      },
      py::arg("machine"), py::arg("pose"),
      R"doc(The tool's compliance at `pose` with the struts as the springs, as `pkm compliance --pose`.

pose: [x_mm, y_mm, z_mm, a_rad, b_rad, c_rad] in the machine's angle convention. Needs the struts' stiffness
(the machine file's stiffness: section, or the springs of its dynamics: section).

Returns a dict: compliance (6, 6) about the tool point, base frame: rows dx dy dz (mm), rx ry rz (rad) per
columns fx fy fz (N), mx my mz (N·mm); dof (the platform motions the mechanism allows);
translational_stiffness_N_um (3,) ascending with translational_directions (3, 3) (unit columns);
rotational_stiffness_Nm_mrad (3,) with rotational_axes (3, 3) (inf: a direction the mechanism does not
allow); strut_stiffness_N_mm (n,) and strut_length_mm (n,) at the pose; strut_lines (n, 6) each strut's
Plücker line about the tool point; pose (the completed pose).)doc");
}

}  // namespace pkm::python
