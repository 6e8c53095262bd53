#pragma once
// NX NURBS records of CL data: the curve being collected. See cl_reader_nurbs.cpp.
#include "program/cl_reader_state.hpp"

namespace pkm::program {

struct ClNurbsState {
  bool collecting = false;
};

}  // namespace pkm::program
