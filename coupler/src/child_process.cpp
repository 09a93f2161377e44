#include "dfc/coupler/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <deque>
#include <fstream>

#include "dfc/common/errors.hpp"
#include "dfc/common/process_status.hpp"

namespace dfc::coupler {

ChildProcess::ChildProcess(const std::filesystem::path& executable, const std::vector<std::string>& args,
                           const std::filesystem::path& stderr_log, const std::filesystem::path& stdout_log)
    : stderr_log_(stderr_log), stdout_log_(stdout_log) {
  int out_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) throw UserError("cannot create a pipe for " + executable.string() + ": " + std::strerror(errno));
  const int err_fd = ::open(stderr_log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (err_fd < 0) {
    ::close(out_pipe[0]);
    ::close(out_pipe[1]);
    throw UserError("cannot write the server log '" + stderr_log.string() + "': " + std::strerror(errno));
  }
  // argv for execv, built before fork: the child must only call async-signal-safe functions.
  std::vector<std::string> argv_strings{executable.string()};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& s : argv_strings) argv.push_back(s.data());
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();

  pid_ = ::fork();
  if (pid_ < 0) throw UserError("cannot start " + executable.string() + ": fork failed: " + std::strerror(errno));
  if (pid_ == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the coupler died before prctl took effect
    ::dup2(out_pipe[1], STDOUT_FILENO);
    ::dup2(err_fd, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    const char message[] = "coupler: exec failed\n";
    (void)!::write(STDERR_FILENO, message, sizeof message - 1);
    ::_exit(127);
  }
  ::close(out_pipe[1]);
  ::close(err_fd);
  stdout_fd_ = out_pipe[0];
}

ChildProcess::~ChildProcess() {
  kill();
  if (stdout_copier_.joinable()) stdout_copier_.join();
  if (stdout_fd_ >= 0) ::close(stdout_fd_);
}

std::string ChildProcess::wait_for_endpoint(std::chrono::milliseconds timeout, const std::string& label) {
  const std::string marker = "DFC-LISTENING ";
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (true) {
    const auto newline = stdout_buffer_.find('\n');
    if (newline != std::string::npos) {
      const std::string line = stdout_buffer_.substr(0, newline);
      stdout_buffer_.erase(0, newline + 1);
      if (line.rfind(marker, 0) == 0) {
        start_stdout_copier();
        return line.substr(marker.size());
      }
      continue;  // some other output before the marker: ignore it
    }
    if (const auto exited = exit_description())
      throw UserError(label + " " + *exited + " before it was ready (no DFC-LISTENING line). Last lines of its stderr (" +
                      stderr_log_.string() + "):\n" + stderr_tail(15));
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now());
    if (left.count() <= 0)
      throw UserError(label + " printed no 'DFC-LISTENING <endpoint>' line within " + std::to_string(timeout.count() / 1000) +
                      " s; is it a protocol v1 server? (run.startup_timeout_s sets the limit)");
    pollfd item{stdout_fd_, POLLIN, 0};
    if (::poll(&item, 1, static_cast<int>(std::min<long>(left.count(), 100))) > 0) {
      char buffer[4096];
      const ssize_t n = ::read(stdout_fd_, buffer, sizeof buffer);
      if (n > 0) stdout_buffer_.append(buffer, std::size_t(n));
      else if (n == 0) {
        wait_exit(std::chrono::milliseconds(500));
        const auto exited = exit_description();
        throw UserError(label + (exited ? " " + *exited : " closed its stdout") + " before printing DFC-LISTENING. Last lines of its stderr (" +
                        stderr_log_.string() + "):\n" + stderr_tail(15));
      }
    }
  }
}

void ChildProcess::start_stdout_copier() {
  // Anything the server prints later goes to a log instead of filling the pipe
  // (a full pipe would block the server).
  const int fd = stdout_fd_;
  stdout_fd_ = -1;
  stdout_copier_ = std::thread([fd, log = stdout_log_, rest = stdout_buffer_] {
    std::ofstream out(log, std::ios::app);
    out << rest;
    char buffer[4096];
    ssize_t n;
    while ((n = ::read(fd, buffer, sizeof buffer)) > 0) out.write(buffer, n).flush();
    ::close(fd);
  });
}

std::optional<std::string> ChildProcess::exit_description() {
  if (!exit_status_ && pid_ > 0) {
    int status = 0;
    if (::waitpid(pid_, &status, WNOHANG) == pid_) exit_status_ = status;
  }
  if (!exit_status_) return std::nullopt;
  return describe_wait_status(*exit_status_);
}

bool ChildProcess::wait_exit(std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!exit_description()) {
    if (std::chrono::steady_clock::now() > until) return false;
    ::usleep(10'000);
  }
  return true;
}

void ChildProcess::kill() {
  if (pid_ > 0 && !exit_description()) {
    ::kill(pid_, SIGKILL);
    int status = 0;
    if (::waitpid(pid_, &status, 0) == pid_) exit_status_ = status;
  }
}

std::string ChildProcess::stderr_tail(std::size_t lines) const {
  std::ifstream in(stderr_log_);
  std::deque<std::string> tail;
  std::string line;
  while (std::getline(in, line)) {
    tail.push_back(line);
    if (tail.size() > lines) tail.pop_front();
  }
  std::string text;
  for (const auto& l : tail) text += "    | " + l + "\n";
  return text.empty() ? "    | (empty)\n" : text;
}

}  // namespace dfc::coupler
