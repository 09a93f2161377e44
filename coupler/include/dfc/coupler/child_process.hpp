#pragma once
// ChildProcess: a server started by the coupler (docs/theory/coupling.md §1: the coupler owns
// the run), on top of dfc::Subprocess. stdout is read for the DFC-LISTENING
// line and then copied to a log file by a small thread (a full pipe would
// block the server); stderr goes straight to a log file so nothing a crashing
// server printed is lost, and its tail can be quoted in the error.
#include <sys/types.h>

#include <chrono>
#include <functional>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "dfc/common/subprocess.hpp"

namespace dfc::coupler {

class ChildProcess {
 public:
  /// Starts `executable args...` with stdout to a pipe and stderr to
  /// `stderr_log`, with `environment` ("NAME=VALUE") added to its environment.
  ChildProcess(const std::filesystem::path& executable, const std::vector<std::string>& args, const std::filesystem::path& stderr_log,
               const std::filesystem::path& stdout_log, const std::vector<std::string>& environment);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// What a server said on stdout before it served (SPEC.md §2, §2.1).
  struct Listening {
    std::string endpoint;        ///< of the line "DFC-LISTENING <endpoint>"
    bool authenticated = false;  ///< the line "DFC-AUTHENTICATION curve" came before it
  };
  /// Waits for the line "DFC-LISTENING <endpoint>" on stdout, noting the
  /// authentication line before it. Throws dfc::UserError if the process
  /// exits or prints nothing in time. `while_waiting` runs every 100 ms and
  /// may throw to give up (e.g. on Ctrl-C).
  Listening wait_for_endpoint(std::chrono::milliseconds timeout, const std::string& label, const std::function<void()>& while_waiting);

  /// nullopt while running; otherwise a description ("exited with status 3",
  /// "was killed by signal 9 (Killed)"). Reaps the child.
  std::optional<std::string> exit_description();
  /// Waits up to `timeout` for the process to exit by itself; true if it did.
  bool wait_exit(std::chrono::milliseconds timeout);
  /// SIGKILL and reap (no-op if already gone).
  void kill();

  /// The last `lines` lines of its stderr log, indented for quoting.
  [[nodiscard]] std::string stderr_tail(std::size_t lines) const;
  [[nodiscard]] pid_t pid() const noexcept { return process_.pid(); }
  [[nodiscard]] const std::filesystem::path& stderr_log() const noexcept { return stderr_log_; }

 private:
  void start_stdout_copier();

  std::filesystem::path stderr_log_;
  std::filesystem::path stdout_log_;
  Subprocess process_;
  std::thread stdout_copier_;
};

}  // namespace dfc::coupler
