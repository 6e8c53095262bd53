// CUTCOM/LEFT|RIGHT|OFF: the path offset by the cutter radius, as the G-code interpreter's G41/G42/G40.
#include "program/cl_reader_cutcom.hpp"

#include <fmt/format.h>

namespace pkm::program {

bool ClReader::cutcom_active() const {
  return cutcom_ && cutcom_->active;
}

Status ClReader::cutcom(const ClStatement& s) {
  if (!s.args.empty() && cl_equals_upper(s.args[0].text, "OFF")) {
    record_event(s);
    return ok_status();
  }
  return error_at(s.args.empty() ? s.at : s.args[0].at, "CUTCOM/LEFT and RIGHT are not supported yet");
}

Status ClReader::compensated(const CanonicalMove& move, ClPosition, std::vector<CanonicalMove>& out) {
  out.push_back(move);
  return ok_status();
}

Status ClReader::flush_compensation(ClPosition) {
  return ok_status();
}

}  // namespace pkm::program
