#pragma once
// What the calibration tests share: the ch5 hexapod of the shipped examples with its drive offsets as
// parameters (18 + 18 + 6 = 42), and random plans around its home.
#include <gtest/gtest.h>

#include <memory>

#include "machine/actuator_offsets.hpp"
#include "test_support.hpp"

namespace pkm::calibration {

/// examples/machines/hexapod_ch5.yaml, loaded with pkm::load_machine_file.
inline const Machine& calib_ch5_machine() {
  static const Machine machine = test::machine_from_example("examples/machines/hexapod_ch5.yaml");
  return machine;
}

/// The ch5 hexapod with zero drive offsets dL1..dL6 as parameters.
inline std::unique_ptr<Mechanism> calib_ch5_model() {
  auto model = with_actuator_offset_parameters(*calib_ch5_machine().mechanism);
  if (!model) throw std::runtime_error(model.error().message);
  return std::move(*model);
}

}  // namespace pkm::calibration
