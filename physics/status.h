// status.h — the one error type of the public API: every fallible call
// returns a Status (or a Result<T> holding one), whose message names the
// function, the culprit and the allowed range. Both are [[nodiscard]].
#pragma once

#include <cstdint>
#include <string>

namespace tandem {

/// What went wrong.
enum class StatusCode : int32_t {
  ok = 0,
  null_handle,        ///< the handle is null
  invalid_handle,     ///< stale (object destroyed), world destroyed, or never valid
  foreign_handle,     ///< a handle of another world where one world was expected
  world_locked,       ///< changes are refused inside world_step()
  invalid_definition, ///< a *Def not made by default_*_def()
  invalid_argument,   ///< a value outside its allowed range or of the wrong kind
  capacity_exceeded,  ///< too many worlds, bodies or shapes
};

/// The outcome of a call: ok, or a code and a message naming the culprit.
struct [[nodiscard]] Status {
  StatusCode code = StatusCode::ok;
  std::string message;  ///< empty when ok
  /// True when the call succeeded.
  bool ok() const { return code == StatusCode::ok; }
};

/// A Status and, when it is ok, a value (a default-constructed T otherwise).
template <typename T>
struct [[nodiscard]] Result {
  Status status;
  T value{};
  /// True when the call succeeded and `value` is meaningful.
  bool ok() const { return status.ok(); }
};

/// The short name of a status code ("stale handle" style, for logs).
const char* status_code_name(StatusCode code);

}  // namespace tandem
