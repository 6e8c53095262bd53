#pragma once
// A planned run on the machine in simulation (docs/simulate.md): the drives' loops follow the run's set
// points (interpolated linearly within each servo period, as servo_run.hpp), on the rigid plant
// (servo_simulator.hpp, the tool where the forward kinematics of the actuators put it) or on the elastic
// machine (coupled_machine.hpp, the tool where the platform's integrated pose puts it), with or without the
// process load and the drives' imperfections. What comes out at every servo tick is the tool's actual point
// and its contour error as a vector: from the nearest point of the commanded path to the actual point, so
// that the errors of runs with effects switched on one by one subtract into each effect's part.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "servo/commanded_path.hpp"
#include "servo/coupled_machine.hpp"
#include "statics/wrench.hpp"

namespace pkm::servo {

/// Which effects a run has.
struct MachineRunSetup {
  bool elastic = true;        ///< the elastic machine (else the rigid plant)
  bool load = true;           ///< the process load (else none)
  bool imperfections = true;  ///< the drives' friction, lost motion, encoder, delay, characteristic
};

/// What every run of one program shares; all must outlive the runs.
struct MachineRunInputs {
  const Machine* machine = nullptr;
  const LoopDesign* design = nullptr;                  ///< with the drives' imperfections
  const ServoPlant* plant = nullptr;                   ///< the rigid plant along the run
  const ServoRunInput* input = nullptr;                ///< set points and commanded poses
  const std::vector<statics::Wrench>* load = nullptr;  ///< per tick, N and N·mm about the tool point
  const CommandedPath* path = nullptr;                 ///< commanded_path(*input, the mechanism's axes)
  std::size_t search_window = 0;                       ///< search_window(*design, *input)
  int steps_per_period = 1;
  CoupledOptions coupled;
};

struct MachineRunTick {
  std::size_t index = 0;
  double time_s = 0.0;
  int line = 0;
  Eigen::Vector3d commanded_mm = Eigen::Vector3d::Zero();  ///< the plan's tool point, base frame
  Eigen::Vector3d actual_mm = Eigen::Vector3d::Zero();     ///< the tool point, base frame (NaN: FK failed)
  Eigen::Vector3d contour_mm = Eigen::Vector3d::Zero();    ///< actual − the nearest commanded point
  const DriveVector* position = nullptr;                   ///< the drives' (actuator side), mm
  const DriveVector* force = nullptr;                      ///< N
};

/// `design` without the drives' imperfections.
LoopDesign ideal_drives(const LoopDesign& design);

/// Runs the program with the effects of `setup`; `on_tick` gets every servo tick in order. Fails, naming
/// the program line, where the machine leaves its reach, a state stops being finite, or on_tick fails.
Status run_machine(const MachineRunInputs& inputs, const MachineRunSetup& setup,
                   const std::function<Status(const MachineRunTick&)>& on_tick);

}  // namespace pkm::servo
