#pragma once
// CUTCOM/LEFT|RIGHT of APT CL data: the compensation state. See cl_reader_cutcom.cpp.
#include "program/cl_reader_state.hpp"
#include "program/ngc_cutter_compensation.hpp"

namespace pkm::program {

struct ClCutcomState {
  /// The compensation stage has been started once: from then on every move goes through it (with
  /// compensation off and its queue empty it lets a move pass unchanged), so that it knows where the tool is.
  bool engaged = false;
  /// CUTCOM/LEFT or RIGHT in effect over a path that is already the tool centre: nothing is offset.
  bool centre_path = false;
  ngc::CutterCompensation compensation;
  Plane plane = Plane::xy;
};

}  // namespace pkm::program
