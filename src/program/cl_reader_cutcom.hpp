#pragma once
// CUTCOM/LEFT|RIGHT of APT CL data: the compensation state. See cl_reader_cutcom.cpp.
#include "program/cl_reader_state.hpp"

namespace pkm::program {

struct ClCutcomState {
  bool active = false;
};

}  // namespace pkm::program
