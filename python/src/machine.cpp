// pkm.Machine: a machine file's machine (mechanism, limits, settings), loaded from a file, YAML text or a
// dict.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "io/input_file.hpp"
#include "io/machine_file.hpp"
#include "io/yaml_reader.hpp"
#include "machine_handle.hpp"

namespace pkm::python {
namespace {

// The tool point as the machine-file reader read it (the text is valid: it has just been loaded).
Eigen::Vector3d tool_of(const std::string& text, const std::string& source, bool planar) {
  auto root = parse_yaml_document(text, source);
  if (!root || !(*root)["tool"]) return Eigen::Vector3d::Zero();
  auto tool = YamlReader(source).point((*root)["tool"], "tool", planar ? 2 : 3);
  return tool ? *tool : Eigen::Vector3d::Zero();
}

py::object optional_value(const std::optional<double>& value) {
  return value ? py::object(py::float_(*value)) : py::none();
}

py::array_t<double> vector_array(const double* values, py::ssize_t count) {
  py::array_t<double> out(count);
  std::copy(values, values + count, out.mutable_data());
  return out;
}

std::string path_text(const py::object& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

const Mechanism& mechanism_of(const Machine& machine) {
  return *machine.mechanism;
}

std::string machine_repr(const Machine& machine) {
  const Mechanism& mech = mechanism_of(machine);
  return fmt::format("<pkm.Machine '{}': {}, {} actuators ({}), angles {}, from {}>", machine.name,
                     to_string(mech.type()), mech.actuator_count(),
                     mech.actuators_are_angles() ? "rad" : "mm", to_string(mech.convention()),
                     machine.source);
}

void bind_machine_properties(MachineClass& cls) {
  cls.def_property_readonly(
         "name", [](const Machine& m) { return m.name; }, "The machine's name (`name:`).")
      .def_property_readonly(
          "source", [](const Machine& m) { return m.source; },
          "Where the machine came from: the file path, or '<text>' / '<dict>' (or the source given).")
      .def_property_readonly(
          "type", [](const Machine& m) { return std::string(to_string(mechanism_of(m).type())); },
          "The mechanism type as the file names it (hexapod, tripod, planar3, ...).")
      .def_property_readonly(
          "actuator_count", [](const Machine& m) { return mechanism_of(m).actuator_count(); },
          "Number of actuators n: the width of ik()'s result and of fk()'s input.")
      .def_property_readonly(
          "angle_convention",
          [](const Machine& m) { return std::string(to_string(mechanism_of(m).convention())); },
          "The convention of the pose angles a, b, c (abc, krylov, euler_zxz); planar machines: abc, phi = "
          "c.")
      .def_property_readonly(
          "controlled_axes",
          [](const Machine& m) {
            const auto c = mechanism_of(m).controlled_axes().controlled;
            return py::make_tuple(c[0], c[1], c[2], c[3], c[4], c[5]);
          },
          "Which of the six pose coordinates (x, y, z, a, b, c) the mechanism controls; it computes the "
          "others.")
      .def_property_readonly(
          "coordinate_names",
          [](const Machine& m) {
            const auto names = pose_coordinate_names(mechanism_of(m));
            return py::make_tuple(names[0], names[1], names[2], names[3], names[4], names[5]);
          },
          "Names of the six pose coordinates in the machine's convention, e.g. ('x','y','z','A','B','C').")
      .def_property_readonly(
          "controlled_names", [](const Machine& m) { return controlled_coordinate_names(mechanism_of(m)); },
          "Names of the controlled coordinates: the columns of jacobian().")
      .def_property_readonly(
          "is_planar", [](const Machine& m) { return mechanism_of(m).is_planar(); },
          "True for planar mechanisms (x, y and phi = c; z, a, b are 0).")
      .def_property_readonly(
          "home",
          [](const Machine& m) {
            const Mechanism& mech = mechanism_of(m);
            const PoseVector home = vector_from_pose(mech.convention(), mech.home());
            return vector_array(home.data(), 6);
          },
          "The home pose, shape (6,): x, y, z mm and a, b, c rad in the machine's angle convention.")
      .def_property_readonly(
          "tool_mm",
          [](const MachineHolder& m) -> py::object {
            const MachineFileFacts* facts = machine_file_facts(m);
            if (!facts) return py::none();
            return vector_array(facts->tool_mm.data(), 3);
          },
          "The tool point in the platform frame, shape (3,), mm (`tool:`; zeros when not given).")
      .def_property_readonly(
          "actuator_limits",
          [](const Machine& m) {
            py::dict d;
            d["min"] = optional_value(m.limits.min);
            d["max"] = optional_value(m.limits.max);
            d["speed"] = optional_value(m.limits.speed);
            d["accel"] = optional_value(m.limits.accel);
            d["force_N"] = optional_value(m.limits.force_N);
            return d;
          },
          "The actuator limits: min, max (mm, or rad for angular actuators), speed (per s), accel (per s²), "
          "force_N (N); None where the file gives none.")
      .def_property_readonly(
          "actuator_unit",
          [](const Machine& m) { return mechanism_of(m).actuators_are_angles() ? "rad" : "mm"; },
          "Unit of the actuator values in this API: 'mm' (struts, carriages) or 'rad' (carriages on a "
          "circle; "
          "the CLI and files show these in degrees).")
      .def_property_readonly(
          "platform_size_mm", [](const Machine& m) { return mechanism_of(m).platform_size_mm(); },
          "The length that scales the angle columns of Jacobians (mm per rad).")
      .def("__repr__", &machine_repr);
}

void bind_machine_loaders(MachineClass& cls) {
  cls.def_static(
         "load",
         [](const py::object& path) {
           const std::string file = path_text(path);
           auto text = read_text_input(file, "machine file");
           if (!text) raise_machine_error(text.error());
           return machine_from_text(*text, file);
         },
         py::arg("path"),
         "Loads a machine file (YAML, docs/machine-file.md), as `pkm ik --machine PATH` does.\n\n"
         "Raises pkm.MachineFileError (with file, line, column, key) for an invalid file, pkm.FileIOError "
         "when "
         "it cannot be read.")
      .def_static(
          "from_yaml",
          [](const std::string& text, const std::string& source) {
            return machine_from_text(normalize_text_input(text), source);
          },
          py::arg("text"), py::arg("source") = "<text>",
          "A machine from machine-file text (YAML); `source` names it in errors and becomes "
          "Machine.source.\n\n"
          "Raises pkm.MachineFileError with line and column in `text`.")
      .def_static(
          "from_dict",
          [](const py::object& data, const std::string& source) {
            const std::string text = py::module_::import("pkm._machine_text")
                                         .attr("machine_json_text")(data, source)
                                         .cast<std::string>();
            return machine_from_text(text, source);
          },
          py::arg("data"), py::arg("source") = "<dict>",
          "A machine from a dict of machine-file entries (as pkm.read_machine_dict gives; units as in files: "
          "mm "
          "and degrees). numpy numbers and arrays are accepted as values.\n\n"
          "The dict is written as pretty-printed JSON (JSON is YAML) with one key or list item per line and "
          "read "
          "as a machine file named `source`. Errors raise pkm.MachineFileError whose `key` names the entry "
          "(e.g. "
          "'limits.actuator_min'); its line and column refer to that JSON text, "
          "pkm._machine_text.machine_json_text(data).");
  cls.def(py::pickle(
      [](const MachineHolder& m) {
        const MachineFileFacts* facts = machine_file_facts(m);
        if (!facts)
          throw py::type_error("this pkm.Machine was not read from a machine text and cannot be pickled");
        return py::make_tuple(facts->text, m->source);
      },
      [](const py::tuple& state) {
        return machine_from_text(state[0].cast<std::string>(), state[1].cast<std::string>());
      }));
}

}  // namespace

void raise_machine_error(const Error& error) {
  if (error.code != ErrorCode::bad_input) raise_error(error);
  const ErrorLocation& at = error.location;
  auto none_if = [](bool empty, py::object value) { return empty ? py::none() : value; };
  const py::object exception = py::module_::import("pkm._errors")
                                   .attr("MachineFileError")(error.message, error_code_name(error.code),
                                                             none_if(at.file.empty(), py::str(at.file)),
                                                             none_if(at.line == 0, py::int_(at.line)),
                                                             none_if(at.column == 0, py::int_(at.column)),
                                                             none_if(at.key.empty(), py::str(at.key)));
  PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(exception.ptr())), exception.ptr());
  throw py::error_already_set();
}

MachineHolder machine_from_text(const std::string& text, const std::string& source) {
  auto machine = parse_machine_text(text, source);
  if (!machine) raise_machine_error(machine.error());
  MachineFileFacts facts;
  facts.tool_mm = tool_of(text, source, machine->mechanism->is_planar());
  facts.text = text;
  return MachineHolder(new Machine(std::move(machine).value()), std::move(facts));
}

const MachineFileFacts* machine_file_facts(const MachineHolder& machine) {
  return std::get_deleter<MachineFileFacts>(machine);
}

MachineClass machine_class(py::module_& m) {
  return py::reinterpret_borrow<MachineClass>(m.attr("Machine"));
}

void bind_machine(py::module_& m) {
  MachineClass cls(
      m, "Machine",
      "A parallel-kinematic machine from a machine file: its mechanism, limits and settings.\n\n"
      "Poses are rows [x, y, z, a, b, c]: the tool point in mm in the base frame and the platform "
      "orientation as three angles in rad in the machine's angle_convention (krylov, abc or "
      "euler_zxz; planar machines use x, y and c = phi). Actuator values are mm, or rad for "
      "angular actuators (actuator_unit). Make one with Machine.load(path), "
      "Machine.from_yaml(text) or Machine.from_dict(d).");
  bind_machine_properties(cls);
  bind_machine_loaders(cls);
  bind_machine_dict(m);
}

}  // namespace pkm::python
