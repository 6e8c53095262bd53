// pkm.read_machine_dict: a machine file as plain Python data (dicts, lists, numbers, texts), to change
// entries and build a variant with Machine.from_dict. Scalars are typed as YAML 1.2's core schema types them
// (what PyYAML-like readers give), so a number stays a number and round-trips exactly through JSON.
#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <regex>
#include <string>

#include "bindings.hpp"
#include "io/yaml_reader.hpp"
#include "machine_handle.hpp"

namespace pkm::python {
namespace {

bool is_one_of(const std::string& text, std::initializer_list<const char*> words) {
  for (const char* word : words) {
    if (text == word) return true;
  }
  return false;
}

// A plain (unquoted, untagged) scalar as the core schema reads it: null, bool, int, float, else text.
py::object plain_scalar(const std::string& text) {
  static const std::regex decimal("[-+]?[0-9]+");
  static const std::regex octal("0o[0-7]+");
  static const std::regex hexadecimal("0x[0-9a-fA-F]+");
  static const std::regex decimal_float("[-+]?(\\.[0-9]+|[0-9]+(\\.[0-9]*)?)([eE][-+]?[0-9]+)?");
  if (is_one_of(text, {"", "~", "null", "Null", "NULL"})) return py::none();
  if (is_one_of(text, {"true", "True", "TRUE"})) return py::bool_(true);
  if (is_one_of(text, {"false", "False", "FALSE"})) return py::bool_(false);
  // Python's int() takes any length, so large integers stay exact.
  if (std::regex_match(text, decimal))
    return py::reinterpret_steal<py::object>(PyLong_FromString(text.c_str(), nullptr, 10));
  if (std::regex_match(text, octal))
    return py::reinterpret_steal<py::object>(PyLong_FromString(text.c_str() + 2, nullptr, 8));
  if (std::regex_match(text, hexadecimal))
    return py::reinterpret_steal<py::object>(PyLong_FromString(text.c_str() + 2, nullptr, 16));
  // strtod rounds correctly, as yaml-cpp's reading of the same text does, so from_dict sees the same double.
  if (std::regex_match(text, decimal_float)) return py::float_(std::strtod(text.c_str(), nullptr));
  const bool negative = !text.empty() && text[0] == '-';
  const std::string unsigned_text =
      !text.empty() && (text[0] == '-' || text[0] == '+') ? text.substr(1) : text;
  if (is_one_of(unsigned_text, {".inf", ".Inf", ".INF"})) return py::float_(negative ? -HUGE_VAL : HUGE_VAL);
  if (is_one_of(text, {".nan", ".NaN", ".NAN"})) return py::float_(std::nan(""));
  return py::str(text);
}

py::object python_value(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      py::dict out;
      for (const auto& item : node) out[py::str(item.first.Scalar())] = python_value(item.second);
      return out;
    }
    case YAML::NodeType::Sequence: {
      py::list out;
      for (const auto& item : node) out.append(python_value(item));
      return out;
    }
    case YAML::NodeType::Scalar:
      // "?" marks a plain scalar; quoted ones ("!") and explicitly tagged ones stay texts.
      return node.Tag() == "?" ? plain_scalar(node.Scalar()) : py::str(node.Scalar());
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      return py::none();
  }
  return py::none();
}

}  // namespace

void bind_machine_dict(py::module_& m) {
  m.def(
      "read_machine_dict",
      [](const py::object& path) {
        const std::string file = py::module_::import("os").attr("fspath")(path).cast<std::string>();
        auto root = load_yaml_file(file, "machine file");
        if (!root) raise_machine_error(root.error());
        return python_value(*root);
      },
      py::arg("path"),
      R"(The machine file at `path` as plain Python data: mappings as dicts (in file order), lists as lists,
scalars typed as YAML 1.2 types them (int, float, bool, None, else str). Units are the file's (mm, degrees).
Change entries and build the variant with Machine.from_dict, e.g.

    d = pkm.read_machine_dict("examples/machines/hexapod_ch5.yaml")
    d["limits"]["actuator_max"] = 950
    variant = pkm.Machine.from_dict(d)

Raises pkm.MachineFileError when the file is not valid YAML (or has a key twice), pkm.FileIOError when it
cannot be read. The machine itself is not checked here: from_dict does that.)");
}

}  // namespace pkm::python
