#pragma once
// The three kinds of failure (CONTRIBUTING.md §7): programmer errors are assertions,
// user errors are typed exceptions carrying one sentence (what, why, how to fix)
// and, for scenario input, the key path; warnings go to the log.
#include <stdexcept>
#include <string>

namespace dfc {

/// A mistake in the user's input. `what()` is a complete sentence for the user.
class UserError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A bad value in a scenario or configuration section.
/// `key_path()` is the dotted path of the offending key ("dem.contact.law"),
/// `reason()` says what was expected; `what()` is "<key_path>: <reason>".
class ConfigError : public UserError {
 public:
  ConfigError(std::string key_path, std::string reason);
  [[nodiscard]] const std::string& key_path() const noexcept { return key_path_; }
  [[nodiscard]] const std::string& reason() const noexcept { return reason_; }

  /// The same error with `prefix` put in front of the key path (used by the
  /// coupler to say which scenario section a server rejected).
  [[nodiscard]] ConfigError with_prefix(const std::string& prefix) const;

 private:
  std::string key_path_;
  std::string reason_;
};

/// A solver cannot continue (instability, non-finite values, broken invariant
/// that depends on input rather than on a programming error).
class SolverError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace dfc
