#pragma once
// Where a file-based library run from Python writes its output set: the caller's `out_dir`, or a temporary
// directory (Python's tempfile, so that it lives where Python puts temporary files) removed afterwards.
#include <pybind11/pybind11.h>

#include <string>

#include "pipeline_support.hpp"

namespace pkm::python {

/// `out_dir`, or a temporary directory removed when this is destroyed.
class RunDirectory {
 public:
  explicit RunDirectory(const py::object& out_dir) {
    if (out_dir.is_none()) {
      temporary_ = py::module_::import("tempfile").attr("TemporaryDirectory")(py::arg("prefix") = "pkm-");
      path_ = temporary_.attr("name").cast<std::string>();
    } else {
      path_ = optional_path(out_dir);
    }
  }
  RunDirectory(const RunDirectory&) = delete;
  RunDirectory& operator=(const RunDirectory&) = delete;
  ~RunDirectory() {
    if (temporary_) temporary_.attr("cleanup")();
  }
  const std::string& path() const { return path_; }
  std::string file(const char* name) const { return path_ + "/" + name; }

 private:
  py::object temporary_;
  std::string path_;
};

}  // namespace pkm::python
