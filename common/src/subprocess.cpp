#include "dfc/common/subprocess.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "dfc/common/errors.hpp"
#include "dfc/common/process_status.hpp"

namespace dfc {

namespace {

std::string system_error(const std::string& what) { return what + ": " + std::strerror(errno); }

// execve needs a path; searching PATH here, before fork, keeps the child to
// async-signal-safe calls only (the supervisor has ZeroMQ I/O threads running).
std::string resolve_executable(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::string_view dirs = path != nullptr ? path : "/usr/bin:/bin";
  while (true) {
    const auto colon = dirs.find(':');
    const std::string dir(dirs.substr(0, colon));
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    if (colon == std::string_view::npos) break;
    dirs.remove_prefix(colon + 1);
  }
  throw UserError("cannot run '" + name + "': not found in PATH");
}

/// This process's environment with `extra` ("NAME=VALUE") added, replacing
/// entries of the same name; built before fork, like the path above.
std::vector<std::string> child_environment(const std::vector<std::string>& extra) {
  const auto name_of = [](std::string_view entry) { return entry.substr(0, entry.find('=')); };
  std::vector<std::string> entries;
  for (char** entry = environ; entry != nullptr && *entry != nullptr; ++entry) {
    const std::string_view text(*entry);
    const bool replaced = std::any_of(extra.begin(), extra.end(), [&](const std::string& e) { return name_of(e) == name_of(text); });
    if (!replaced) entries.emplace_back(text);
  }
  entries.insert(entries.end(), extra.begin(), extra.end());
  return entries;
}

std::vector<char*> c_strings(std::vector<std::string>& texts) {
  std::vector<char*> pointers;
  for (auto& text : texts) pointers.push_back(text.data());
  pointers.push_back(nullptr);
  return pointers;
}

std::string join(const std::vector<std::string>& argv) {
  std::string text;
  for (const auto& arg : argv) text += (text.empty() ? "" : " ") + arg;
  return text;
}

}  // namespace

Subprocess::Subprocess(const std::vector<std::string>& argv, const std::filesystem::path& stderr_log,
                       const std::vector<std::string>& environment)
    : command_(join(argv)) {
  if (argv.empty()) throw UserError("no command given");
  const std::string executable = resolve_executable(argv[0]);
  std::vector<std::string> args = argv;
  const std::vector<char*> c_argv = c_strings(args);
  std::vector<std::string> env = child_environment(environment);
  const std::vector<char*> c_env = c_strings(env);

  int out_pipe[2];
  int exec_pipe[2];  // reports a failed execve back to us: stays empty when exec succeeds (CLOEXEC)
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) throw UserError(system_error("cannot create a pipe"));
  UniqueFd out_read(out_pipe[0]);
  UniqueFd out_write(out_pipe[1]);
  if (::pipe2(exec_pipe, O_CLOEXEC) != 0) throw UserError(system_error("cannot create a pipe"));
  UniqueFd exec_read(exec_pipe[0]);
  UniqueFd exec_write(exec_pipe[1]);
  if (stderr_log.empty()) {
    stderr_file_ = UniqueFd(::memfd_create("dfc-server-stderr", MFD_CLOEXEC));
    if (!stderr_file_.valid()) throw UserError(system_error("cannot create a buffer for the stderr of '" + command_ + "'"));
  } else {
    // Read-write: stderr_tail() reads the log back with pread.
    stderr_file_ = UniqueFd(::open(stderr_log.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
    if (!stderr_file_.valid()) throw UserError(system_error("cannot write the log '" + stderr_log.string() + "'"));
  }
  UniqueFd null_in(::open("/dev/null", O_RDONLY | O_CLOEXEC));
  const pid_t parent = ::getpid();

  pid_ = ::fork();
  if (pid_ < 0) throw UserError(system_error("cannot start '" + command_ + "': fork failed"));
  if (pid_ == 0) {
    // Child: async-signal-safe calls only.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the supervisor died before prctl took effect
    ::dup2(null_in.get(), STDIN_FILENO);
    ::dup2(out_write.get(), STDOUT_FILENO);
    ::dup2(stderr_file_.get(), STDERR_FILENO);
    ::execve(executable.c_str(), c_argv.data(), c_env.data());
    const int error = errno;
    (void)!::write(exec_write.get(), &error, sizeof error);
    ::_exit(127);
  }
  ::setpgid(pid_, pid_);  // also here: whichever of parent and child runs first
  out_write.reset();
  exec_write.reset();
  int exec_errno = 0;
  ssize_t got = 0;
  do got = ::read(exec_read.get(), &exec_errno, sizeof exec_errno);
  while (got < 0 && errno == EINTR);
  if (got == static_cast<ssize_t>(sizeof exec_errno)) {
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    throw UserError("cannot run '" + executable + "': " + std::strerror(exec_errno));
  }
  stdout_ = std::move(out_read);
}

Subprocess::~Subprocess() { kill(); }

bool Subprocess::fill_stdout(std::chrono::milliseconds timeout) {
  if (stdout_eof_) return false;
  pollfd item{stdout_.get(), POLLIN, 0};
  const int ready = ::poll(&item, 1, static_cast<int>(std::max<std::int64_t>(timeout.count(), 0)));
  if (ready <= 0) return true;
  char chunk[4096];
  const ssize_t n = ::read(stdout_.get(), chunk, sizeof chunk);
  if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN)) {
    stdout_eof_ = true;
    return false;
  }
  if (n > 0) stdout_buffer_.append(chunk, static_cast<std::size_t>(n));
  return true;
}

std::optional<std::string> Subprocess::read_line(std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (const auto newline = stdout_buffer_.find('\n'); newline != std::string::npos) {
      std::string line = stdout_buffer_.substr(0, newline);
      stdout_buffer_.erase(0, newline + 1);
      return line;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now());
    if (left.count() <= 0 || !fill_stdout(left)) return std::nullopt;
  }
}

std::string Subprocess::read_rest(std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (true) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now());
    if (left.count() <= 0 || !fill_stdout(left)) break;
  }
  return std::exchange(stdout_buffer_, {});
}

Subprocess::StdoutHandover Subprocess::release_stdout() {
  stdout_eof_ = true;
  return {std::move(stdout_), std::exchange(stdout_buffer_, {})};
}

std::optional<int> Subprocess::poll_exit() {
  if (exit_status_ || pid_ < 0) return exit_status_;
  int status = 0;
  const pid_t done = ::waitpid(pid_, &status, WNOHANG);
  if (done == pid_) exit_status_ = status;
  return exit_status_;
}

std::optional<int> Subprocess::wait_exit(std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!poll_exit() && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return poll_exit();
}

void Subprocess::kill() noexcept {
  if (pid_ < 0 || exit_status_) return;
  ::kill(-pid_, SIGKILL);
  ::kill(pid_, SIGKILL);  // in case it left its process group
  int status = 0;
  if (::waitpid(pid_, &status, 0) == pid_) exit_status_ = status;
}

std::string Subprocess::stderr_tail(std::size_t max_lines) const {
  struct stat info {};
  if (::fstat(stderr_file_.get(), &info) != 0 || info.st_size <= 0) return {};
  constexpr off_t kWindow = 64 * 1024;
  const off_t start = info.st_size > kWindow ? info.st_size - kWindow : 0;
  std::string text(static_cast<std::size_t>(info.st_size - start), '\0');
  const ssize_t n = ::pread(stderr_file_.get(), text.data(), text.size(), start);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!text.empty() && text.back() == '\n') text.pop_back();
  // Walk back over max_lines newlines; the tail starts just after the last one passed.
  std::size_t begin = text.size();
  std::size_t lines = 0;
  while (begin > 0) {
    if (text[begin - 1] == '\n' && ++lines == max_lines) break;
    --begin;
  }
  return text.substr(begin);
}

std::string Subprocess::describe_status(int status) { return describe_wait_status(status); }

}  // namespace dfc
