#pragma once
// Expected failures as values: a Result<T> holds either a T or an Error (code + one-line message).
// Exceptions are kept for broken contracts only (see docs/ARCHITECTURE.md, "Errors").
#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace pkm {

enum class ErrorCode {
  bad_input,       ///< malformed file, argument or value
  unreachable,     ///< a pose no actuator setting can reach
  not_converged,   ///< an iterative solver stopped without meeting its tolerance
  singular,        ///< a singular (or badly conditioned) configuration
  wrong_branch,    ///< a solution exists but in another assembly mode / branch than asked for
  limit_exceeded,  ///< an actuator or joint limit is violated
  unsupported,     ///< the mechanism does not offer this operation
  io,              ///< a file could not be read or written
};

const char* to_string(ErrorCode code);

/// Where in an input file an error is, as fields (the message says the same in words): bindings raise typed
/// exceptions from it and editors jump to it. An empty file means the error is not about a file's content.
struct ErrorLocation {
  std::string file;
  int line = 0;     ///< 1-based; 0: unknown
  int column = 0;   ///< 1-based; 0: unknown
  std::string key;  ///< of a structured file, with indices ("base_joints[2]"); empty for part programs
};

struct Error {
  ErrorCode code;
  std::string message;       ///< one line, names file/line/field and units where they apply
  ErrorLocation location{};  ///< filled by the file readers (YAML files, G-code, CL data)
  /// Machine-readable details beyond the message, as JSON text (empty: none): e.g. the whole extent of a
  /// program's excursion out of the workspace. The command line prints them with --json.
  std::string details_json{};
};

template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : state_(std::move(value)) {}      // NOLINT(google-explicit-constructor): ergonomic returns
  Result(Error error) : state_(std::move(error)) {}  // NOLINT(google-explicit-constructor)

  bool ok() const { return state_.index() == 0; }
  explicit operator bool() const { return ok(); }

  const T& value() const& {
    assert(ok());
    return std::get<0>(state_);
  }
  T& value() & {
    assert(ok());
    return std::get<0>(state_);
  }
  T&& value() && {
    assert(ok());
    return std::get<0>(std::move(state_));
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

  const Error& error() const {
    assert(!ok());
    return std::get<1>(state_);
  }

 private:
  std::variant<T, Error> state_;
};

/// Result of an operation that yields nothing on success.
struct Unit {};
using Status = Result<Unit>;
inline Status ok_status() {
  return Unit{};
}

inline Error make_error(ErrorCode code, std::string message) {
  return Error{code, std::move(message)};
}

}  // namespace pkm
