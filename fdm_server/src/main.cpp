// fdm_server: the FLAC3D-style explicit finite-difference continuum solver as a
// protocol v1 server. Run `fdm_server --help` for the configure section.
#include <memory>

#include "dfc/fdm/fdm_backend.hpp"
#include "dfc/fdm/fdm_config.hpp"
#include "dfc/protocol/server.hpp"

int main(int argc, char** argv) {
  return dfc::protocol::run_server_main(
      argc, argv,
      {"fdm_server", "explicit Lagrangian finite-difference continuum (FLAC3D-style, small strain) for DEM-FDM coupling",
       dfc::fdm::fdm_config_help(), [] { return std::make_unique<dfc::fdm::FdmBackend>(); },
       [](const nlohmann::json& section) { (void)dfc::fdm::load_fdm_model(section); }});
}
