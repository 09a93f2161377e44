#include "command_runner.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dfc::testing {

pid_t start_command(const std::vector<std::string>& argv, const std::filesystem::path& output_file) {
  std::vector<std::string> args = argv;
  std::vector<char*> raw;
  for (auto& a : args) raw.push_back(a.data());
  raw.push_back(nullptr);
  const int fd = ::open(output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write " + output_file.string());
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    ::execv(raw[0], raw.data());
    ::_exit(127);
  }
  ::close(fd);
  if (pid < 0) throw std::runtime_error("fork failed");
  return pid;
}

int wait_command(pid_t pid, std::chrono::milliseconds timeout) {
  // The limits are those of the everyday build; the sanitized build runs the
  // same programs several times slower (cmake/Sanitizers.cmake).
  const auto until = std::chrono::steady_clock::now() + timeout * DFC_TEST_TIMEOUT_SCALE;
  int status = 0;
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > until) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      break;
    }
    ::usleep(20'000);
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

CommandResult run_command(const std::vector<std::string>& argv, std::chrono::milliseconds timeout) {
  static int counter = 0;
  const auto output = std::filesystem::temp_directory_path() / ("dfc-e2e-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".log");
  const auto start = std::chrono::steady_clock::now();
  CommandResult result;
  result.exit_status = wait_command(start_command(argv, output), timeout);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.output = read_text(output);
  std::filesystem::remove(output);
  return result;
}

void wait_for_exchanges(const std::filesystem::path& log) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (read_text(log).find("exchanges,") == std::string::npos && std::chrono::steady_clock::now() < until) ::usleep(50'000);
}

std::vector<pid_t> child_pids(pid_t parent) {
  std::vector<pid_t> children;
  for (const auto& task : std::filesystem::directory_iterator("/proc/" + std::to_string(parent) + "/task")) {
    std::ifstream in(task.path() / "children");
    pid_t pid = 0;
    while (in >> pid) children.push_back(pid);
  }
  return children;
}

std::string process_name(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/cmdline");
  std::string first;
  std::getline(in, first, '\0');
  return first;
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::filesystem::path fresh_directory(const std::string& name) {
  const auto dir = std::filesystem::current_path() / "e2e-output" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace dfc::testing
