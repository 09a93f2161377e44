#include "runner.hpp"

#include <optional>
#include <string>

#include "context.hpp"
#include "fresh_server.hpp"

namespace dfc::conformance {

namespace {

std::string_view milestone_text(Milestone milestone) {
  switch (milestone) {
    case Milestone::none: return "nothing";
    case Milestone::listening: return "a listening server (server.listening)";
    case Milestone::greeted: return "a successful hello (handshake.hello)";
    case Milestone::configured: return "a successful configure (configure.accepted)";
    case Milestone::stepped: return "a successful advance (advance.one_step)";
  }
  return "?";
}

/// Why `check` cannot run now, if it cannot. After a failed check the next
/// one gets a fresh server brought to the state it needs, so that one
/// failure never makes another check fail; a server that cannot be brought
/// there again leaves that state unreached for the checks after it.
std::optional<std::string> blocked(const Check& check, Context& context) {
  if (check.needs == Milestone::none) return std::nullopt;
  if (!context.reached.contains(check.needs)) return "not run: needs " + std::string(milestone_text(check.needs)) + ", which failed";
  if (context.needs_fresh_server && !check.same_process) {
    try {
      bring_fresh_server_to(context, check.needs);
      context.needs_fresh_server = false;
    } catch (const std::exception& e) {
      context.reached.erase(check.needs);
      return std::string("not run: ") + e.what();
    }
  }
  if (context.unavailable) return "not run: " + *context.unavailable;
  return std::nullopt;
}

/// Why `check` does not apply to this server, if it does not: its rule came
/// with a later minor version than the server declares (SPEC.md §1).
std::optional<std::string> not_yet(const Check& check, const Context& context) {
  if (check.since_minor == 0 || !context.declared_minor || *context.declared_minor >= check.since_minor) return std::nullopt;
  return "a rule of protocol " + std::to_string(protocol::kVersionMajor) + "." + std::to_string(check.since_minor) +
         "; the server declares " + std::to_string(protocol::kVersionMajor) + "." + std::to_string(*context.declared_minor);
}

/// One line per check, whatever the server sent.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

enum class Outcome { pass, fail, skip };

struct Result {
  Outcome outcome = Outcome::pass;
  std::string why;
};

Result run_one(const Check& check, Context& context) {
  try {
    check.run(context);
    return {};
  } catch (const NotApplicable& e) {
    return {Outcome::skip, e.what()};
  } catch (const ServerGone& e) {
    context.unavailable = e.what();
    return {Outcome::fail, e.what()};
  } catch (const std::exception& e) {
    return {Outcome::fail, e.what()};
  }
}

/// The server must keep running after anything it was sent (SPEC.md §7).
void ping_after(Context& context, Result& result) {
  try {
    context.expect_alive();
  } catch (const std::exception& e) {
    const std::string why = std::string("afterwards the server did not answer ping: ") + e.what();
    if (dynamic_cast<const ServerGone*>(&e) != nullptr) context.unavailable = e.what();
    // A ping that misses its deadline means the server is hung; waiting on
    // it in every remaining check would only multiply the timeout.
    else if (dynamic_cast<const protocol::TimeoutError*>(&e) != nullptr)
      context.unavailable = "the server stopped answering (" + std::string(e.what()) + ")";
    result.why = result.outcome == Outcome::fail ? result.why + "; " + why : why;
    result.outcome = Outcome::fail;
  }
}

}  // namespace

Tally run_checks(const std::vector<Check>& checks, Context& context, std::ostream& out) {
  Tally tally;
  for (const Check& check : checks) {
    Result result;
    if (const auto skipped = not_yet(check, context)) {  // before blocked(), which may start a fresh server
      result = {Outcome::skip, *skipped};
    } else if (const auto reason = blocked(check, context)) {
      result = {Outcome::fail, *reason};
    } else {
      result = run_one(check, context);
      if (check.ping_after && !context.unavailable) ping_after(context, result);
      if (result.outcome == Outcome::pass && check.establishes != Milestone::none) context.reached.insert(check.establishes);
      if (result.outcome == Outcome::fail && context.server_started()) context.needs_fresh_server = true;
    }
    switch (result.outcome) {
      case Outcome::pass:
        ++tally.passed;
        out << "PASS " << check.name << std::endl;
        break;
      case Outcome::fail:
        ++tally.failed;
        out << "FAIL " << check.name << ": " << one_line(result.why) << std::endl;
        break;
      case Outcome::skip:
        ++tally.skipped;
        out << "SKIP " << check.name << ": " << one_line(result.why) << std::endl;
        break;
    }
  }
  return tally;
}

}  // namespace dfc::conformance
