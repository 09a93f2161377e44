#include "dfc/coupler/child_process.hpp"

#include <unistd.h>

#include <fstream>
#include <sstream>

#include "dfc/common/errors.hpp"
#include "dfc/protocol/authentication.hpp"
#include "dfc/protocol/transport.hpp"

namespace dfc::coupler {

namespace {

std::vector<std::string> command_line(const std::filesystem::path& executable, const std::vector<std::string>& args) {
  std::vector<std::string> argv{executable.string()};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

}  // namespace

ChildProcess::ChildProcess(const std::filesystem::path& executable, const std::vector<std::string>& args,
                           const std::filesystem::path& stderr_log, const std::filesystem::path& stdout_log,
                           const std::vector<std::string>& environment)
    : stderr_log_(stderr_log), stdout_log_(stdout_log), process_(command_line(executable, args), stderr_log, environment) {}

ChildProcess::~ChildProcess() {
  kill();
  if (stdout_copier_.joinable()) stdout_copier_.join();
}

ChildProcess::Listening ChildProcess::wait_for_endpoint(std::chrono::milliseconds timeout, const std::string& label,
                                                        const std::function<void()>& while_waiting) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  bool authenticated = false;
  while (true) {
    while_waiting();
    // Short reads so that an exit is noticed within 100 ms.
    if (const auto line = process_.read_line(std::chrono::milliseconds(100))) {
      if (line->starts_with(protocol::kListeningMarker)) {
        start_stdout_copier();
        return {line->substr(protocol::kListeningMarker.size()), authenticated};
      }
      if (*line == protocol::authentication::kAnnouncement) authenticated = true;
      continue;  // some other output before the marker: ignore it
    }
    if (process_.stdout_closed()) (void)wait_exit(std::chrono::milliseconds(500));
    if (const auto exited = exit_description())
      throw UserError(label + " " + *exited + " before it was ready (no DFC-LISTENING line). Last lines of its stderr (" +
                      stderr_log_.string() + "):\n" + stderr_tail(15));
    if (process_.stdout_closed())
      throw UserError(label + " closed its stdout before printing DFC-LISTENING. Last lines of its stderr (" + stderr_log_.string() + "):\n" +
                      stderr_tail(15));
    if (std::chrono::steady_clock::now() >= until)
      throw UserError(label + " printed no 'DFC-LISTENING <endpoint>' line within " + std::to_string(timeout.count() / 1000) +
                      " s; is it a protocol v1 server? (run.startup_timeout_s sets the limit)");
  }
}

void ChildProcess::start_stdout_copier() {
  stdout_copier_ = std::thread([handover = process_.release_stdout(), log = stdout_log_] {
    std::ofstream out(log, std::ios::app);
    out << handover.buffered;
    char buffer[4096];
    ssize_t n;
    while ((n = ::read(handover.pipe.get(), buffer, sizeof buffer)) > 0) out.write(buffer, n).flush();
  });
}

std::optional<std::string> ChildProcess::exit_description() {
  const auto status = process_.poll_exit();
  if (!status) return std::nullopt;
  return Subprocess::describe_status(*status);
}

bool ChildProcess::wait_exit(std::chrono::milliseconds timeout) { return process_.wait_exit(timeout).has_value(); }

void ChildProcess::kill() { process_.kill(); }

std::string ChildProcess::stderr_tail(std::size_t lines) const {
  std::istringstream tail(process_.stderr_tail(lines));
  std::string text, line;
  while (std::getline(tail, line)) text += "    | " + line + "\n";
  return text.empty() ? "    | (empty)\n" : text;
}

}  // namespace dfc::coupler
