#pragma once
// Runs a command as a child process for end-to-end tests: the real
// executables, as a user would start them (CONTRIBUTING.md §8).
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace dfc::testing {

struct CommandResult {
  int exit_status = -1;  ///< exit code, or 128 + signal
  std::string output;    ///< stdout and stderr together
  double seconds = 0.0;
};

/// Starts `argv` with stdout+stderr to a temporary file; returns its pid.
pid_t start_command(const std::vector<std::string>& argv, const std::filesystem::path& output_file);
/// Waits for `pid` up to `timeout` x DFC_TEST_TIMEOUT_SCALE (4 in the sanitized build, else 1; SIGKILL
/// after that); returns the status as in CommandResult. run_command waits the same way.
int wait_command(pid_t pid, std::chrono::milliseconds timeout);
/// start + wait + read the output.
CommandResult run_command(const std::vector<std::string>& argv, std::chrono::milliseconds timeout);

/// Waits until the coupler's output in `log` shows that the exchanges have
/// begun (its plan line, "Run '...': N exchanges, ..."), at most 30 s.
void wait_for_exchanges(const std::filesystem::path& log);

/// Child processes of `parent` (from /proc), e.g. the servers a coupler started.
std::vector<pid_t> child_pids(pid_t parent);
/// The command line of `pid` (argv[0] only).
std::string process_name(pid_t pid);

std::string read_text(const std::filesystem::path& file);
/// A fresh empty folder under the build tree for one test's outputs.
std::filesystem::path fresh_directory(const std::string& name);

}  // namespace dfc::testing
