// SPEC.md §2, §4: shutdown gets bye, then the process exits with status 0;
// stdout carried nothing but the listening line.
#include <sys/wait.h>

#include "check.hpp"
#include "context.hpp"
#include "expectations.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;

namespace {

constexpr std::chrono::seconds kExitDeadline{5};

void shutdown_gets_bye(Context& context) {
  context.set_exit_expected(true);  // the server may exit right after sending bye
  expect_type(context.request(protocol::type::shutdown), protocol::type::bye);
}

void process_exits_zero(Context& context) {
  context.set_exit_expected(true);
  const auto status = context.server().wait_exit(kExitDeadline);
  expect(status.has_value(), "the server did not exit within " + std::to_string(kExitDeadline.count()) + " s of shutdown");
  expect(WIFEXITED(*status) && WEXITSTATUS(*status) == 0,
         "after shutdown the server " + Subprocess::describe_status(*status) + ", expected status 0");
}

void stdout_has_only_the_listening_line(Context& context) {
  const std::string rest = context.server().read_rest(std::chrono::milliseconds(200));
  expect(rest.empty(), "stdout carried more than the listening line (diagnostics belong on stderr): \"" + rest.substr(0, 200) + "\"");
}

}  // namespace

std::vector<Check> shutdown_checks() {
  using M = Milestone;
  return {
      {"shutdown.bye", "shutdown gets bye", M::listening, M::none, false, shutdown_gets_bye},
      {"shutdown.exit_status", "the process exits with status 0 within 5 s of bye", M::listening, M::none, false, process_exits_zero, 0,
       true},
      {"shutdown.stdout_clean", "stdout carried nothing but the listening line", M::listening, M::none, false,
       stdout_has_only_the_listening_line, 0, true},
  };
}

}  // namespace dfc::conformance
