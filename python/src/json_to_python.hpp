#pragma once
// The library's JSON summaries (nlohmann::json) as plain Python values, so that a summary the CLI writes to
// summary.json arrives in Python as the dict json.load would give: objects as dicts, arrays as lists,
// numbers as int or float, null as None.
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

namespace pkm::python {

pybind11::object python_from_json(const nlohmann::json& value);

}  // namespace pkm::python
