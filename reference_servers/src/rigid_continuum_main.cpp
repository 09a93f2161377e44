// rigid_continuum_server — reference continuum whose interface never moves.
#include <memory>

#include "dfc/fdm/fdm_config.hpp"
#include "dfc/protocol/server.hpp"
#include "dfc/reference/rigid_continuum_backend.hpp"

int main(int argc, char** argv) {
  return dfc::protocol::run_server_main(
      argc, argv,
      {"rigid_continuum_server",
       "reference continuum: the fdm_server interface held rigidly fixed (zero velocity, any force)",
       "The same section as fdm_server (only mesh and coupling.group matter; the rest is\n"
       "validated and ignored, so a scenario swaps continua by changing `program`):\n\n" +
           dfc::fdm::fdm_config_help(),
       [] { return std::make_unique<dfc::reference::RigidContinuumBackend>(); },
       [](const nlohmann::json& section) { (void)dfc::fdm::load_fdm_model(section); }});
}
