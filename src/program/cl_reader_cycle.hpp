#pragma once
// CYCLE/… of APT CL data: the state between CYCLE/<kind> and CYCLE/OFF. See cl_reader_cycle.cpp.
#include <Eigen/Geometry>
#include <optional>

#include "program/cl_reader_state.hpp"
#include "program/ngc_canned_cycle.hpp"

namespace pkm::program {

/// One value of a CYCLE definition and where it was written (for errors).
struct ClCycleValue {
  std::optional<double> value;
  ClPosition at;
};

struct ClCycleState {
  bool active = false;
  // The definition (CYCLE/<kind>,…), lengths in mm along the tool axis from the hole top (the GOTO).
  int code = 810;           ///< the G-code cycle ×10 that drills each hole: 730, 810, 820, 830, 840, 850
  ClPosition at;            ///< the CYCLE statement
  double depth_mm = 0.0;    ///< below the hole top
  double r_mm = 0.0;        ///< R plane above the hole top
  ClCycleValue retract_mm;  ///< RTRCTO: where the tool goes between holes, above the hole top
  bool retract_initial = false;  ///< G98 (or RTRCTO,AUTO): back to the level the series started from
  double dwell_s = 0.0;
  double peck_mm = 0.0;      ///< first (or every) peck; 0: none
  double sub_peck_mm = 0.0;  ///< later pecks when they differ from the first (1STPECK/SUBPECK, PECKING)
  ClPosition depth_at, r_at, peck_at, dwell_at;
  double feed_mm_min = 0.0;
  double feed_per_rev_mm = 0.0;  ///< MMPR/IPR (or the FEDRAT per revolution in effect); 0: per minute
  // The series of holes drilled with one tool axis: the frame they are drilled in (tool axis = +Z, origin at
  // the first hole's top) and the canned-cycle engine's memory between them (G98's initial level).
  bool series = false;
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();  ///< series frame → CL frame
  Eigen::Vector3d frame_axis = Eigen::Vector3d::UnitZ();
  ngc::CycleMemory memory;
};

}  // namespace pkm::program
