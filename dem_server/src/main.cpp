// dem_server: the DEM particle solver as a protocol v1 server.
//   dem_server --help      lists the configure section and the contact-law registry
//   dem_server --bind tcp://127.0.0.1:*
//   dem_server --check-config SECTION.json   parse a configure section only
#include <memory>

#include "dfc/dem/dem_backend.hpp"
#include "dfc/dem/dem_config.hpp"
#include "dfc/protocol/server.hpp"

int main(int argc, char** argv) {
  return dfc::protocol::run_server_main(
      argc, argv,
      {"dem_server", "DEM of spheres (PFC-style linear contact, triangle-facet walls, pile) as a protocol v1 server",
       dfc::dem::dem_config_help(), [] { return std::make_unique<dfc::dem::DemBackend>(); },
       [](const nlohmann::json& section) { (void)dfc::dem::parse_dem_config(section); }});
}
