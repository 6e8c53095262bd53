#pragma once
// The name of a canonical move's kind, as `pkm interpret` prints it and the Python module returns it.
#include "program/canonical_program.hpp"

namespace pkm::program {

inline const char* move_kind_name(MoveKind kind) {
  switch (kind) {
    case MoveKind::rapid:
      return "rapid";
    case MoveKind::line:
      return "line";
    case MoveKind::arc:
      return "arc";
    case MoveKind::dwell:
      return "dwell";
  }
  return "?";
}

}  // namespace pkm::program
