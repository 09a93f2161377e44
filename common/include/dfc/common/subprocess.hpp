#pragma once
// Subprocess: a solver server started and watched by another program — the
// coupler (which owns the run, docs/theory/coupling.md §1) or the conformance checker (which
// tests one server). One implementation, so both start, read, reap and kill
// a server the same way.
//
// stdout is a pipe, read line by line (the DFC-LISTENING line, SPEC.md §2);
// stderr goes to a file — the caller's log, or an anonymous in-memory file —
// so nothing a crashing server printed is lost and its tail can be quoted.
// stdin is /dev/null. The child runs in its own process group (a Ctrl-C at
// the terminal reaches only the supervisor, which then shuts the servers down
// in order) and is SIGKILLed, group and all, when this object goes away, and
// by the kernel if the supervisor itself dies (PR_SET_PDEATHSIG).
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "dfc/common/unique_fd.hpp"

namespace dfc {

class Subprocess {
 public:
  /// Starts argv[0] (searched in PATH when it has no '/') with argv[1..],
  /// stderr to `stderr_log` (created or truncated) or, when empty, to an
  /// anonymous in-memory file. `environment` entries ("NAME=VALUE") are added
  /// to (or replace those of) this process's environment, which the child
  /// inherits: a way to hand it what must not be on its command line, which
  /// every user of the host can read. Throws dfc::UserError naming the command
  /// if it cannot be executed.
  explicit Subprocess(const std::vector<std::string>& argv, const std::filesystem::path& stderr_log = {},
                      const std::vector<std::string>& environment = {});
  ~Subprocess();
  Subprocess(const Subprocess&) = delete;
  Subprocess& operator=(const Subprocess&) = delete;

  /// The next stdout line without its '\n'; nullopt if none is complete
  /// within `timeout` or stdout reached end of file first (see stdout_closed()).
  [[nodiscard]] std::optional<std::string> read_line(std::chrono::milliseconds timeout);
  /// Everything stdout still holds, reading until end of file or `timeout`.
  [[nodiscard]] std::string read_rest(std::chrono::milliseconds timeout);
  /// True once stdout reached end of file.
  [[nodiscard]] bool stdout_closed() const noexcept { return stdout_eof_; }
  /// Hands the stdout pipe over (e.g. to a thread that copies it to a log),
  /// with what was read but not yet returned as `buffered`. Reading here ends.
  struct StdoutHandover {
    UniqueFd pipe;
    std::string buffered;
  };
  [[nodiscard]] StdoutHandover release_stdout();

  /// Raw waitpid status once the process has exited (reaps it); nullopt while it runs.
  [[nodiscard]] std::optional<int> poll_exit();
  /// Waits up to `timeout` for the process to exit by itself.
  [[nodiscard]] std::optional<int> wait_exit(std::chrono::milliseconds timeout);
  /// SIGKILL to the whole process group, then reap; no-op once reaped.
  void kill() noexcept;

  /// The last `max_lines` lines the process wrote to stderr.
  [[nodiscard]] std::string stderr_tail(std::size_t max_lines) const;
  [[nodiscard]] const std::string& command() const noexcept { return command_; }
  [[nodiscard]] pid_t pid() const noexcept { return pid_; }

  /// "exited with status 3", "was killed by signal 6 (Aborted)".
  [[nodiscard]] static std::string describe_status(int status);

 private:
  /// Appends what stdout has within `timeout`; false at end of file.
  bool fill_stdout(std::chrono::milliseconds timeout);

  pid_t pid_ = -1;
  std::optional<int> exit_status_;
  UniqueFd stdout_;
  UniqueFd stderr_file_;
  bool stdout_eof_ = false;
  std::string stdout_buffer_;
  std::string command_;
};

}  // namespace dfc
