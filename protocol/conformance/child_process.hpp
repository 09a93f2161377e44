#pragma once
// ChildProcess: the server under test (or a one-shot `--help` run of it).
//
// stdout is a pipe, read for the DFC-LISTENING line (SPEC.md §2) and checked
// to carry nothing else; stderr goes to an unlinked temporary file so that its
// tail can be quoted when the server misbehaves, without a thread to drain it.
// The child runs in its own process group and is SIGKILLed (group and all)
// when this object goes away, and by the kernel if the checker itself dies.
#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "unique_fd.hpp"

namespace dfc::conformance {

class ChildProcess {
 public:
  /// Starts argv[0] (searched in PATH when it has no '/') with argv[1..].
  /// Throws std::runtime_error naming the command if it cannot be executed.
  explicit ChildProcess(const std::vector<std::string>& argv);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// The next stdout line without its '\n'; nullopt if none is complete
  /// within `timeout` or stdout reached end of file first.
  [[nodiscard]] std::optional<std::string> read_line(std::chrono::milliseconds timeout);
  /// Everything stdout still holds, reading until end of file or `timeout`.
  [[nodiscard]] std::string read_rest(std::chrono::milliseconds timeout);

  /// Raw waitpid status once the process has exited (reaps it); nullopt while it runs.
  [[nodiscard]] std::optional<int> poll_exit();
  /// Waits up to `timeout` for the process to exit by itself.
  [[nodiscard]] std::optional<int> wait_exit(std::chrono::milliseconds timeout);
  /// SIGKILL to the whole process group, then reap; no-op once reaped.
  void kill() noexcept;

  /// The last `max_lines` lines the process wrote to stderr.
  [[nodiscard]] std::string stderr_tail(std::size_t max_lines) const;
  [[nodiscard]] const std::string& command() const noexcept { return command_; }

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

}  // namespace dfc::conformance
