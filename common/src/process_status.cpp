#include "dfc/common/process_status.hpp"

#include <sys/wait.h>

#include <cstring>

namespace dfc {

std::string describe_wait_status(int status) {
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::strsignal(sig);
    return "was killed by signal " + std::to_string(sig) + (name != nullptr ? " (" + std::string(name) + ")" : "");
  }
  return "stopped (wait status " + std::to_string(status) + ")";
}

}  // namespace dfc
