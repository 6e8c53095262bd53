#include "core/result.hpp"

namespace pkm {

const char* to_string(ErrorCode code) {
  switch (code) {
    case ErrorCode::bad_input:
      return "bad input";
    case ErrorCode::unreachable:
      return "unreachable";
    case ErrorCode::not_converged:
      return "not converged";
    case ErrorCode::singular:
      return "singular";
    case ErrorCode::wrong_branch:
      return "wrong assembly mode";
    case ErrorCode::limit_exceeded:
      return "limit exceeded";
    case ErrorCode::unsupported:
      return "unsupported";
    case ErrorCode::io:
      return "i/o";
  }
  return "error";
}

}  // namespace pkm
