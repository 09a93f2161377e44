#pragma once
// Error codes of protocol v1 (SPEC.md §7) and the exception that carries one.
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace dfc::protocol {

enum class ErrorCode {
  bad_message,       ///< header not JSON, required field missing or of the wrong type
  unknown_type,      ///< message type not defined by this version
  version_mismatch,  ///< protocol major versions differ
  out_of_order,      ///< message not allowed in the server's current state
  bad_array,         ///< array descriptor and frame disagree, or wrong dtype/shape for its use
  too_large,         ///< a frame or the frame count exceeds the announced limits
  step_mismatch,     ///< advance.step is not the server's current step
  bad_config,        ///< configure section rejected; body.key names the key path
  unsupported,       ///< the server lacks the capability the request needs
  solver_failure,    ///< the solver cannot continue (instability, non-finite state)
  bad_checkpoint,    ///< 1.3: a checkpoint file that cannot be written, read, or belongs to another solver, version or section
  internal           ///< a bug in the server
};

[[nodiscard]] std::string_view error_code_name(ErrorCode code) noexcept;
[[nodiscard]] std::optional<ErrorCode> error_code_from_name(std::string_view name) noexcept;

/// An error that becomes an `error` reply. `key` is set for bad_config.
class ProtocolError : public std::runtime_error {
 public:
  ProtocolError(ErrorCode code, const std::string& message, std::string key = {})
      : std::runtime_error(message), code_(code), key_(std::move(key)) {}
  [[nodiscard]] ErrorCode code() const noexcept { return code_; }
  [[nodiscard]] const std::string& key() const noexcept { return key_; }

 private:
  ErrorCode code_;
  std::string key_;
};

}  // namespace dfc::protocol
