// The order of the table is the order of a session (SPEC.md §5.1): the
// command-line checks need no server; the others drive one server process
// from fresh through greeted, configured and running to closed.
#include "check.hpp"

namespace dfc::conformance {

const std::vector<Check>& all_checks() {
  static const std::vector<Check> table = [] {
    std::vector<Check> checks;
    for (auto group : {command_line_checks, handshake_checks, heartbeat_checks, authentication_checks, malformed_message_checks, configure_checks, interface_checks,
                       checkpoint_checks_configured, advance_checks, checkpoint_checks_running, shutdown_checks}) {
      auto more = group();
      checks.insert(checks.end(), more.begin(), more.end());
    }
    return checks;
  }();
  return table;
}

}  // namespace dfc::conformance
