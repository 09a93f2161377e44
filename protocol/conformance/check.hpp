#pragma once
// One conformance check: a name, what it needs from the checks before it,
// and a small function that throws when the server breaks the contract.
#include <stdexcept>
#include <string_view>
#include <vector>

namespace dfc::conformance {

class Context;

/// States of the session that later checks build on. A check whose
/// prerequisite failed is reported as FAIL "not run" instead of producing a
/// confusing OUT_OF_ORDER of its own; after any other failure the next check
/// gets a fresh server brought to the state it needs (fresh_server.hpp).
enum class Milestone { none, listening, greeted, configured, stepped };

struct Check {
  std::string_view name;     ///< "group.what", printed in the PASS/FAIL line
  std::string_view summary;  ///< one line for --list
  Milestone needs = Milestone::none;
  Milestone establishes = Milestone::none;  ///< reached when this check passes
  bool ping_after = true;  ///< then verify the server still answers ping (it kept running)
  void (*run)(Context& context) = nullptr;
  /// The minor version (of major 1) the rule appeared in (SPEC.md §1): a
  /// server that declares an older one in hello_ok is not held to it (SKIP).
  /// 0: every 1.x server.
  int since_minor = 0;
  /// The check examines the process the check before it used (the exit after
  /// shutdown), so it never gets the fresh server that follows a failure.
  bool same_process = false;
};

/// The server broke the contract; what() says how, in one sentence.
class CheckFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The check means nothing for this server (e.g. interface inputs of an
/// uncoupled one); reported as SKIP, counted neither passed nor failed.
class NotApplicable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws CheckFailure(why) unless `condition`.
inline void expect(bool condition, const std::string& why) {
  if (!condition) throw CheckFailure(why);
}

/// Every check, in the order they run (check_table.cpp).
[[nodiscard]] const std::vector<Check>& all_checks();

// The groups the table is assembled from, one file each.
[[nodiscard]] std::vector<Check> command_line_checks();
[[nodiscard]] std::vector<Check> handshake_checks();
[[nodiscard]] std::vector<Check> heartbeat_checks();
[[nodiscard]] std::vector<Check> authentication_checks();
[[nodiscard]] std::vector<Check> malformed_message_checks();
[[nodiscard]] std::vector<Check> configure_checks();
[[nodiscard]] std::vector<Check> interface_checks();
[[nodiscard]] std::vector<Check> checkpoint_checks_configured();
[[nodiscard]] std::vector<Check> advance_checks();
[[nodiscard]] std::vector<Check> checkpoint_checks_running();
[[nodiscard]] std::vector<Check> shutdown_checks();

}  // namespace dfc::conformance
