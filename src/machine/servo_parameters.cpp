#include "machine/servo_parameters.hpp"

namespace pkm {

const char* to_string(ServoTuning tuning) {
  switch (tuning) {
    case ServoTuning::technical_optimum:
      return "technical_optimum";
    case ServoTuning::symmetric_optimum:
      return "symmetric_optimum";
    case ServoTuning::explicit_gains:
      return "explicit";
  }
  return "technical_optimum";
}

}  // namespace pkm
