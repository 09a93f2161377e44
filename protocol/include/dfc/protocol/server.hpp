#pragma once
// The generic protocol v1 server: command line, socket, lifecycle, limits.
#include <functional>
#include <memory>
#include <string>

#include "dfc/protocol/message.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::protocol {

struct ServerProgram {
  std::string name;         ///< executable name, e.g. "fdm_server"
  std::string summary;      ///< one line for --help
  std::string config_help;  ///< text describing the configure section (for --help)
  std::function<std::unique_ptr<SolverBackend>()> make_backend;
  /// Reads a configure section without building the model (--check-config):
  /// throws ConfigError naming the key for bad input.
  std::function<void(const nlohmann::json& section)> check_config;
  /// The minor protocol version the server declares (hello_ok, every reply).
  /// A server declaring 1.6 or later runs a heartbeat (SPEC.md §9.1). Only a
  /// test fixture playing an older server sets less than kVersionMinor.
  int declared_minor = kVersionMinor;
  /// Whether a server declaring 1.6 or later runs its heartbeat; false only in
  /// a test fixture that breaks that rule on purpose.
  bool heartbeat = true;
  /// Whether the pongs of a server declaring 1.8 or later carry `progress`
  /// (SPEC.md §9.1); false only in a test fixture that breaks that rule on purpose.
  bool progress = true;
  /// Whether a server declaring 1.7 or later uses the key file DFC_KEY_FILE
  /// names (SPEC.md §2.1); false only in a test fixture that breaks that rule on purpose.
  bool authentication = true;
  /// Lines of options the program reads itself before run_server_main (for
  /// --help; each "  --option  text\n"), e.g. dem_server's --mpi.
  std::string extra_options = {};
};

/// main() of every server: parses --bind/--help/--version/--check-config, binds a ROUTER
/// socket (and, beside it, the heartbeat's, served by a thread of its own),
/// both CURVE servers with the key of the file DFC_KEY_FILE names, if it names one,
/// prints "DFC-LISTENING <endpoint>" on stdout and serves one session until
/// shutdown. Returns the process exit status.
int run_server_main(int argc, char** argv, const ServerProgram& program);

}  // namespace dfc::protocol
