#pragma once
// Words for a child process's end, shared by the coupler (which supervises the
// servers it starts) and the conformance checker (which supervises the server
// under test), so both report a crash the same way.
#include <string>

namespace dfc {

/// "exited with status 3", "was killed by signal 9 (Killed)", from a raw waitpid status.
[[nodiscard]] std::string describe_wait_status(int status);

}  // namespace dfc
