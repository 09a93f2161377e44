// dfc_conformance: runs the whole protocol v1 contract (protocol/SPEC.md)
// against one server program and reports each check.
//
//   dfc_conformance [--config FILE] [--timeout S] -- COMMAND [ARGS...]
//
// 1. read the command line;  2. run the check table (it starts the server);
// 3. print the tally and, after a failure, the tail of the stderr of the
//    process that failed last.
// The server process is killed when the context goes away, whatever happened.
#include <iostream>

#include "check.hpp"
#include "context.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/common/version.hpp"
#include "dfc/protocol/message.hpp"
#include "options.hpp"
#include "runner.hpp"

namespace {

int print_list() {
  for (const auto& check : dfc::conformance::all_checks()) std::cout << check.name << "  " << check.summary << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace dfc::conformance;
  ParsedCommandLine command_line;
  try {
    command_line = parse_command_line(argc, argv);
  } catch (const dfc::UserError& e) {
    std::cerr << "dfc_conformance: " << e.what() << "\n";
    return 2;
  }
  switch (command_line.action) {
    case Action::help: std::cout << usage_text(); return 0;
    case Action::version:
      std::cout << "dfc_conformance " << dfc::project_version() << " (protocol " << dfc::protocol::version_string() << ")\n";
      return 0;
    case Action::list: return print_list();
    case Action::run: break;
  }

  Context context(std::move(command_line.options));
  const Tally tally = run_checks(all_checks(), context, std::cout);
  std::cout << tally.passed << " passed, " << tally.failed << " failed" << std::endl;
  if (tally.failed > 0 && context.server_started()) {
    // The process of the last failure: the current one, unless it was replaced by a fresh one.
    const std::string tail = context.needs_fresh_server ? context.server().stderr_tail(kStderrTailLines) : context.replaced_stderr_tail;
    if (!tail.empty()) std::cerr << "--- last lines of the server's stderr ---\n" << tail << "\n";
  }
  return tally.failed == 0 ? 0 : 1;
}
