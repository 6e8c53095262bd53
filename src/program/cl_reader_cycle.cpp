// CYCLE/DRILL|DEEP|TAP|BORE|… … CYCLE/OFF: every GOTO in between is a hole, drilled along the tool axis the
// way the G-code canned cycles drill along Z.
#include "program/cl_reader_cycle.hpp"

#include <fmt/format.h>

namespace pkm::program {

bool ClReader::cycle_active() const {
  return cycle_ && cycle_->active;
}

Status ClReader::cycle(const ClStatement& s) {
  return error_at(s.at, "CYCLE is not supported yet");
}

Status ClReader::cycle_point(const ClStatement& s, const ClPoint&) {
  return error_at(s.at, "CYCLE is not supported yet");
}

}  // namespace pkm::program
