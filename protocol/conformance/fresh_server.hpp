#pragma once
// A fresh server for the checks after a failed one, so that no failure makes
// another check fail: the server command is started again and brought back
// to the state the next check needs, by the requests that reached it the
// first time (SPEC.md §5.1).
#include "check.hpp"

namespace dfc::conformance {

class Context;

/// Replaces the server process with a new one of the same command and
/// brings it to `milestone`: hello (greeted), configure with the --config
/// section and the interface exchange that passed before (configured), one
/// step (stepped). Updates what the context knows of the session (hello_ok,
/// step). Throws CheckFailure naming the request that failed.
void bring_fresh_server_to(Context& context, Milestone milestone);

}  // namespace dfc::conformance
