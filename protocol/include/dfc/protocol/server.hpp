#pragma once
// The generic protocol v1 server: command line, socket, lifecycle, limits.
#include <functional>
#include <memory>
#include <string>

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
};

/// main() of every server: parses --bind/--help/--version/--check-config, binds a ROUTER
/// socket, prints "DFC-LISTENING <endpoint>" on stdout and serves one session
/// until shutdown. Returns the process exit status.
int run_server_main(int argc, char** argv, const ServerProgram& program);

}  // namespace dfc::protocol
