// SPEC.md §2: every server accepts --help and --version, prints text and exits 0.
#include <sys/wait.h>

#include <algorithm>
#include <cctype>

#include "check.hpp"
#include "context.hpp"

namespace dfc::conformance {

namespace {

void expect_flag_prints_text(Context& context, const std::string& flag) {
  std::vector<std::string> argv = context.options().command;
  argv.push_back(flag);
  Subprocess process(argv);
  const auto started = std::chrono::steady_clock::now();
  const std::string text = process.read_rest(context.timeout());
  const auto used = std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - started);
  const auto status = process.wait_exit(std::max(context.timeout() - used, std::chrono::milliseconds(200)));
  expect(status.has_value(), "'" + process.command() + "' did not exit within the timeout");
  expect(WIFEXITED(*status) && WEXITSTATUS(*status) == 0, "'" + process.command() + "' " + Subprocess::describe_status(*status) +
                                                              ", expected status 0; stderr: " + process.stderr_tail(3));
  expect(std::any_of(text.begin(), text.end(), [](unsigned char c) { return std::isgraph(c) != 0; }),
         "'" + process.command() + "' printed nothing on stdout");
}

void help_exits_zero(Context& context) { expect_flag_prints_text(context, "--help"); }
void version_exits_zero(Context& context) { expect_flag_prints_text(context, "--version"); }

}  // namespace

std::vector<Check> command_line_checks() {
  return {
      {"cli.help", "COMMAND --help prints text on stdout and exits 0", Milestone::none, Milestone::none, false, help_exits_zero},
      {"cli.version", "COMMAND --version prints text on stdout and exits 0", Milestone::none, Milestone::none, false, version_exits_zero},
  };
}

}  // namespace dfc::conformance
