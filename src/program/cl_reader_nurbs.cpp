// NX NURBS/ records: the spline evaluated into line moves within the tolerance.
#include "program/cl_reader_nurbs.hpp"

#include <fmt/format.h>

namespace pkm::program {

bool ClReader::nurbs_collecting() const {
  return nurbs_ && nurbs_->collecting;
}

Status ClReader::nurbs(const ClStatement& s) {
  return error_at(s.at, "NURBS is not supported yet");
}

Status ClReader::nurbs_continue(const ClStatement&, bool& consumed) {
  consumed = false;
  return ok_status();
}

Status ClReader::nurbs_finish(ClPosition) {
  return ok_status();
}

}  // namespace pkm::program
