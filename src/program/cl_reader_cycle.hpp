#pragma once
// CYCLE/… of APT CL data: the state between CYCLE/<kind> and CYCLE/OFF. See cl_reader_cycle.cpp.
#include "program/cl_reader_state.hpp"

namespace pkm::program {

struct ClCycleState {
  bool active = false;
};

}  // namespace pkm::program
