#pragma once
// Command line of dfc_conformance:
//   dfc_conformance [--config FILE] [--timeout S] -- COMMAND [ARGS...]
#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace dfc::conformance {

struct Options {
  std::string section_json = "{}";          ///< sent verbatim in `configure` (the bytes of --config FILE)
  std::string config_path;                  ///< empty: the default section `{}`
  std::chrono::milliseconds timeout{10'000};  ///< per request, per process start, per --help run
  std::vector<std::string> command;         ///< COMMAND ARGS... of the server under test
};

enum class Action { run, help, version, list };

struct ParsedCommandLine {
  Action action = Action::run;
  Options options;
};

/// Parses argv; throws dfc::UserError with a sentence saying what is wrong.
[[nodiscard]] ParsedCommandLine parse_command_line(int argc, char** argv);

/// The --help text.
[[nodiscard]] std::string usage_text();

}  // namespace dfc::conformance
