// continuum_server: the axisymmetric large-strain continuum of the jacked
// open-ended pile (docs/continuum_pile.md) as a protocol v1 server. Run
// `continuum_server --help` for the configure section.
#include <memory>

#include "dfc/continuum/continuum_backend.hpp"
#include "dfc/continuum/continuum_config.hpp"
#include "dfc/protocol/server.hpp"

int main(int argc, char** argv) {
  return dfc::protocol::run_server_main(
      argc, argv,
      {"continuum_server", "axisymmetric large-strain continuum of a jacked open-ended pile (rigid pile, frictional contact; drained)",
       dfc::continuum::continuum_config_help(), [] { return std::make_unique<dfc::continuum::ContinuumBackend>(); },
       [](const nlohmann::json& section) { (void)dfc::continuum::load_pile_model(section); }});
}
