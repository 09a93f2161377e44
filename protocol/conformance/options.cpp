#include "options.hpp"

#include <cmath>
#include <fstream>
#include <string_view>

#include "dfc/common/command_line.hpp"
#include "dfc/common/durations.hpp"
#include "dfc/common/errors.hpp"

namespace dfc::conformance {

namespace {

std::string read_file_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) throw UserError("cannot read the configure section '" + path + "'; --config needs a readable JSON file");
  // Byte for byte: the server hashes exactly what it receives (SPEC.md §4.2).
  std::string bytes(static_cast<std::size_t>(file.tellg()), '\0');
  file.seekg(0);
  if (!file.read(bytes.data(), static_cast<std::streamsize>(bytes.size())))
    throw UserError("cannot read the configure section '" + path + "'");
  return bytes;
}

std::chrono::milliseconds parse_seconds(const std::string& text) {
  return milliseconds_from_seconds(parse_number_option("--timeout", text, Bounds{0.0, 3600.0, true}));
}

}  // namespace

ParsedCommandLine parse_command_line(int argc, char** argv) {
  ParsedCommandLine parsed;
  int i = 1;
  for (; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UserError("option " + std::string(arg) + " needs a value; see dfc_conformance --help");
      return argv[++i];
    };
    if (arg == "--") {
      ++i;
      break;
    }
    if (arg == "--help" || arg == "-h") parsed.action = Action::help;
    else if (arg == "--version") parsed.action = Action::version;
    else if (arg == "--list") parsed.action = Action::list;
    else if (arg == "--config") parsed.options.config_path = value();
    else if (arg == "--timeout") parsed.options.timeout = parse_seconds(value());
    else if (arg.starts_with("-")) throw UserError("unknown option '" + std::string(arg) + "'; see dfc_conformance --help");
    else break;  // the command starts here (the '--' is recommended but optional)
  }
  for (; i < argc; ++i) parsed.options.command.emplace_back(argv[i]);
  if (parsed.action != Action::run) return parsed;
  if (parsed.options.command.empty())
    throw UserError("no server command given; usage: dfc_conformance [--config FILE] [--timeout S] -- COMMAND [ARGS...]");
  if (!parsed.options.config_path.empty()) parsed.options.section_json = read_file_bytes(parsed.options.config_path);
  return parsed;
}

std::string usage_text() {
  return R"(dfc_conformance — checks that a solver server speaks DFC protocol v1 (protocol/SPEC.md)

Usage: dfc_conformance [--config FILE] [--timeout S] -- COMMAND [ARGS...]
       dfc_conformance --help | --version | --list

Starts `COMMAND ARGS --bind tcp://127.0.0.1:*` with DFC_KEY_FILE naming a key
file of its own (SPEC.md section 2.1), reads its DFC-LISTENING line (and the
line 'DFC-AUTHENTICATION curve' before it: then it connects with the key),
connects, and runs every check of the contract: handshake, version refusal,
heartbeat, authentication (strangers get no answer), state ordering,
malformed and oversized frames, interface exchange, step semantics, query,
snapshot, shutdown and exit status. It also runs
`COMMAND ARGS --help` and `COMMAND ARGS --version`. Prints one line per check
("PASS name", "FAIL name: why", or "SKIP name: why" when the server's
capabilities make a check meaningless or its rule came in a later protocol
minor than the server declares in hello_ok) and ends with "N passed, M
failed". The check after a failed one runs against a fresh process of the
same command, brought back to the state it needs, so one broken rule fails
one check.
Exit status: 0 if no check failed, 1 if one did, 2 for a usage error.

Options:
  --config FILE   the section sent in 'configure', byte for byte (default: {})
  --timeout S     deadline in seconds for each reply, for the listening line
                  and for --help/--version runs (default 10)
  --list          print the names of the checks and exit
  --help          this text;  --version  checker and protocol versions
)";
}

}  // namespace dfc::conformance
