// pkm's executor behind the C functions of pkmexec_bridge.h: the machine file is read once, at module load,
// for the drives' software stops, their step, their home and the override's rates (execution/
// machine_headroom.hpp); the servo-thread calls use only the executor (execution/step_executor.hpp).
#include "pkmexec_bridge.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "execution/machine_headroom.hpp"
#include "execution/step_executor.hpp"
#include "machine/machine.hpp"
#include "machine/mechanism.hpp"
#include "module_machine.hpp"

struct pkmexec_executor {
  pkm::Machine machine;
  std::unique_ptr<pkm::execution::StepExecutor> executor;
  int drives = 0;
  double step = 0.001;  ///< joints' unit per step (mm or deg)
  pkm::execution::StepArray home{};
  pkm::execution::StepArray position{};
  int refused = 0;  ///< 0, PKMEXEC_REFUSED or PKMEXEC_NOT_HANDED_OVER
};

namespace {

using pkm::linuxcnc::copy_message;

pkm::execution::StepArray to_steps(const long long* values, int n) {
  pkm::execution::StepArray out{};
  for (int j = 0; j < n; ++j) out[j] = values[j];
  return out;
}

}  // namespace

extern "C" {

pkmexec_executor* pkmexec_create(const char* machine_file, double period_s, char* error, size_t error_size) {
  try {
    auto loaded = pkm::linuxcnc::load_module_machine(machine_file, error, error_size);
    if (!loaded) return nullptr;
    auto e = std::make_unique<pkmexec_executor>();
    e->machine = std::move(*loaded);
    e->step = e->machine.drives.step.value_or(0.001);
    auto settings = pkm::execution::executor_settings(e->machine, e->step, period_s);
    if (!settings) {
      copy_message(settings.error().message, error, error_size);
      return nullptr;
    }
    const pkm::Mechanism& mechanism = *e->machine.mechanism;
    e->drives = mechanism.actuator_count();
    auto home = mechanism.inverse(mechanism.home());
    if (!home) {
      copy_message(e->machine.source + ": home is out of reach: " + home.error().message, error, error_size);
      return nullptr;
    }
    const double unit = pkm::execution::step_in_actuator_units(e->machine, e->step);
    for (int j = 0; j < e->drives; ++j) e->home[j] = std::llround((*home)[j] / unit);
    e->position = e->home;
    e->executor = std::make_unique<pkm::execution::StepExecutor>(*settings);
    return e.release();
  } catch (const std::exception& ex) {
    copy_message(std::string("cannot set up the executor: ") + ex.what(), error, error_size);
    return nullptr;
  }
}

void pkmexec_free(pkmexec_executor* executor) {
  delete executor;
}

int pkmexec_drive_count(const pkmexec_executor* executor) {
  return executor->drives;
}

double pkmexec_step(const pkmexec_executor* executor) {
  return executor->step;
}

void pkmexec_home_steps(const pkmexec_executor* executor, long long* steps) {
  for (int j = 0; j < executor->drives; ++j) steps[j] = executor->home[j];
}

int pkmexec_start(pkmexec_executor* executor, const long long* start, int handed_over) {
  const pkm::execution::StepArray wanted = to_steps(start, executor->drives);
  // Within one step: the interpolator's discreteness correction may start a program on the step next to the
  // nearest one (the drives then make that step in the first period).
  bool elsewhere = false;
  for (int j = 0; j < executor->drives; ++j)
    elsewhere = elsewhere || std::llabs(wanted[j] - executor->position[j]) > 1;
  executor->refused = !handed_over ? PKMEXEC_NOT_HANDED_OVER : elsewhere ? PKMEXEC_REFUSED : 0;
  if (executor->refused != 0) return -1;
  executor->executor->start(wanted);
  return 0;
}

int pkmexec_active(const pkmexec_executor* executor) {
  const pkm::execution::ExecutionState state = executor->executor->state();
  return executor->refused == 0 && (state == pkm::execution::ExecutionState::running ||
                                    state == pkm::execution::ExecutionState::starved)
             ? 1
             : 0;
}

void pkmexec_follow(pkmexec_executor* executor, const double* position) {
  if (pkmexec_active(executor)) return;
  for (int j = 0; j < executor->drives; ++j)
    executor->position[j] = std::llround(position[j] / executor->step);
}

int pkmexec_has_room(const pkmexec_executor* executor) {
  return executor->refused == 0 && executor->executor->has_room() ? 1 : 0;
}

int pkmexec_push(pkmexec_executor* executor, int line, const double* ideal, const long long* position) {
  pkm::execution::NominalPeriod period;
  for (int j = 0; j < executor->drives; ++j) {
    period.ideal_steps[j] = ideal[j];
    period.position_steps[j] = position[j];
  }
  period.line = line;
  return executor->executor->push(period) ? 0 : -1;
}

void pkmexec_end_of_program(pkmexec_executor* executor) {
  executor->executor->end_of_program();
}

int pkmexec_state(const pkmexec_executor* executor) {
  return executor->refused != 0 ? executor->refused : static_cast<int>(executor->executor->state());
}

void pkmexec_period(pkmexec_executor* executor, double override_factor, int hold, int abort,
                    struct pkmexec_period_out* out) {
  pkm::execution::ExecutedPeriod period;
  // Only a program that moves the drives sets where they are; otherwise they stay where they were followed.
  const bool moving = pkmexec_active(executor) != 0;
  executor->executor->period({override_factor, hold != 0, abort != 0}, period);
  const pkm::execution::StepArray before = executor->position;
  if (moving) executor->position = period.position_steps;
  for (int j = 0; j < executor->drives; ++j) {
    out->position[j] = executor->position[j];
    out->steps[j] = executor->position[j] - before[j];  // the drives' own steps, a start's step included
    out->set_point[j] = moving ? period.set_point_steps[j] : static_cast<double>(executor->position[j]);
  }
  out->line = period.line;
  out->factor = period.factor;
  out->tau = period.tau_periods;
  out->state = pkmexec_state(executor);
}

int pkmexec_fault_line(const pkmexec_executor* executor) {
  return executor->executor->fault_line();
}

long pkmexec_periods_ahead(const pkmexec_executor* executor) {
  return executor->executor->periods_ahead();
}

}  // extern "C"
