#include "program/move_output.hpp"

namespace pkm::program {

void MoveOutput::attach(CanonicalProgram& program, MoveSink sink) {
  program_ = &program;
  sink_ = std::move(sink);
  held_.reset();
  count_ = 0;
  status_ = ok_status();
}

Status MoveOutput::push(const CanonicalMove& move) {
  ++count_;
  if (!sink_) {
    program_->moves.push_back(move);
    return ok_status();
  }
  if (held_ && status_) status_ = sink_(*held_);
  held_ = move;
  return status_;
}

CanonicalMove* MoveOutput::last() {
  if (!sink_) return program_->moves.empty() ? nullptr : &program_->moves.back();
  return held_ ? &*held_ : nullptr;
}

Status MoveOutput::flush() {
  if (sink_ && held_ && status_) status_ = sink_(*held_);
  held_.reset();
  return status_;
}

}  // namespace pkm::program
