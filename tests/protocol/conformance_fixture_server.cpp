// conformance_fixture_server: a protocol v1 server around FixtureBackend,
// for the tests of dfc_conformance and the coupler. `--break throw|shape|crash|hang|
// no-force-monitor|nan-velocity|huge-particle-count|unsent-progress-monitor|malformed-progress-monitors|no-heartbeat|no-authentication|accept-surplus-input|
// deadlock-advance|no-progress` makes it misbehave on purpose; every other option is the generic
// server's (--bind, --help, --version, ...). `--protocol-minor N` makes it
// declare 1.N instead of the current minor and behave as a server of that
// version where the rules differ (SPEC.md §1): below 1.8 no progress in the pongs, below 1.7 no authentication, below 1.6 no heartbeat, below
// 1.5 no progress_monitors, below 1.3 checkpoint is UNKNOWN_TYPE, below 1.2
// no monitor_units, below 1.1 surplus input arrays are ignored.
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>

#include "dfc/protocol/server.hpp"
#include "fixture_backend.hpp"

int main(int argc, char** argv) {
  using dfc::protocol::testing::Breakage;
  Breakage breakage = Breakage::none;
  int declared_minor = dfc::protocol::kVersionMinor;
  std::vector<char*> server_args{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--break") == 0 && i + 1 < argc) {
      const auto parsed = dfc::protocol::testing::breakage_from_name(argv[++i]);
      if (!parsed) {
        std::cerr << "conformance_fixture_server: --break takes throw, shape, crash, hang, no-force-monitor, nan-velocity, huge-particle-count, unsent-progress-monitor, malformed-progress-monitors, no-heartbeat, no-authentication, accept-surplus-input, deadlock-advance or no-progress, not '" << argv[i] << "'\n";
        return 2;
      }
      breakage = *parsed;
    } else if (std::strcmp(argv[i], "--protocol-minor") == 0 && i + 1 < argc) {
      declared_minor = std::atoi(argv[++i]);
      if (declared_minor < 0 || declared_minor > dfc::protocol::kVersionMinor) {
        std::cerr << "conformance_fixture_server: --protocol-minor takes 0.." << dfc::protocol::kVersionMinor << ", not '" << argv[i] << "'\n";
        return 2;
      }
    } else {
      server_args.push_back(argv[i]);
    }
  }
  server_args.push_back(nullptr);  // argv convention: argv[argc] is null

  dfc::protocol::ServerProgram program{
      "conformance_fixture_server",
      "a trivial provides_interface continuum for testing dfc_conformance (--break MODE breaks it on purpose)",
      "  side       integer >= 2, default 2: the interface is a side x side grid of nodes 1 m apart in z = 0\n"
      "  advance_s  number in [0, 60], default 0: seconds each advance takes (a slow solver)\n"
      "  interface  boolean, default true: false narrows the capabilities to snapshot, for a run of this server alone",
      [breakage, declared_minor] { return std::make_unique<dfc::protocol::testing::FixtureBackend>(breakage, declared_minor); },
      {}};
  program.declared_minor = declared_minor;
  program.heartbeat = breakage != Breakage::no_heartbeat;  // the generic server runs it, not the backend
  program.authentication = breakage != Breakage::no_authentication;
  program.progress = breakage != Breakage::no_progress;
  return dfc::protocol::run_server_main(static_cast<int>(server_args.size() - 1), server_args.data(), program);
}
