#pragma once
// Runs the check table against one server and prints one line per check.
#include <ostream>
#include <vector>

#include "check.hpp"

namespace dfc::conformance {

class Context;

struct Tally {
  int passed = 0;
  int failed = 0;
  int skipped = 0;
};

/// Runs `checks` in order, printing "PASS name", "FAIL name: why" or
/// "SKIP name: why" to `out` as each finishes. Never waits longer than the
/// context's per-request timeout on any reply. After a failed check the next
/// one runs against a fresh server process brought to the state it needs
/// (fresh_server.hpp), so each failure is reported once, by its own check.
[[nodiscard]] Tally run_checks(const std::vector<Check>& checks, Context& context, std::ostream& out);

}  // namespace dfc::conformance
