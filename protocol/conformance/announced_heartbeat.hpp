#pragma once
// The heartbeat endpoint a server announced in hello_ok (SPEC.md §9.1),
// checked once for the checks that talk to it (heartbeat.*, authentication.*).
#include <string>

namespace dfc::conformance {

class Context;

/// hello_ok.heartbeat_endpoint: a non-empty endpoint on the loopback. Throws
/// CheckFailure naming what is wrong when it is absent or malformed.
[[nodiscard]] std::string announced_endpoint(const Context& context);

}  // namespace dfc::conformance
