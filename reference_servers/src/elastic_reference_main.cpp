// elastic_reference_server — reference continuum: the fdm_server mesh solved
// statically (implicit linear elasticity), condensed to the coupling interface.
#include <memory>

#include "dfc/fdm/fdm_config.hpp"
#include "dfc/protocol/server.hpp"
#include "dfc/reference/elastic_reference_backend.hpp"

int main(int argc, char** argv) {
  return dfc::protocol::run_server_main(
      argc, argv,
      {"elastic_reference_server",
       "reference continuum: static linear elasticity on the fdm_server mesh, condensed to the interface",
       "The same section as fdm_server. The mesh, the boundaries, gravity and the initial stress\n"
       "are used as fdm_server uses them; material.model must be \"elastic\" and coupling.role\n"
       "\"provider\". Each advance returns the static equilibrium under the interface forces\n"
       "received (displacement relative to the initial, geostatic state) and the velocity that\n"
       "reaches it over the advance. damping, mass_scaling and threads are validated and ignored:\n"
       "there is no time integration (quasi-static, no inertia, no plasticity).\n\n" +
           dfc::fdm::fdm_config_help(),
       [] { return std::make_unique<dfc::reference::ElasticReferenceBackend>(); },
       [](const nlohmann::json& section) { (void)dfc::fdm::load_fdm_model(section); }});
}
