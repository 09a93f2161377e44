// dem_server: the DEM particle solver as a protocol v1 server.
//   dem_server --help      lists the configure section and the contact-law registry
//   dem_server --bind tcp://127.0.0.1:*
//   dem_server --check-config SECTION.json   parse a configure section only
//   mpiexec -n 4 dem_server --mpi --bind ...  the body decomposed over 4 processes (mpi_server.hpp)
#include <iostream>
#include <memory>
#include <string_view>

#include "dfc/dem/dem_backend.hpp"
#include "dfc/dem/dem_config.hpp"
#include "dfc/protocol/server.hpp"
#ifdef DFC_DEM_MPI
#include "dfc/dem/distributed_engine.hpp"
#include "dfc/dem/mpi_server.hpp"
#endif

int main(int argc, char** argv) {
  dfc::protocol::ServerProgram program{
      "dem_server", "DEM of spheres (PFC-style linear contact, triangle-facet walls, pile) as a protocol v1 server",
      dfc::dem::dem_config_help(), [] { return std::make_unique<dfc::dem::DemBackend>(); },
      [](const nlohmann::json& section) { (void)dfc::dem::parse_dem_config(section); }};
  program.extra_options =
      "  --mpi                  run as one of the processes of 'mpiexec -n N dem_server --mpi ...': the body is decomposed\n"
      "                         over them, rank 0 binds and speaks (the scenario key participants.dem.mpi_ranks starts it so;\n"
      "                         docs/determinism.md section 3); needs a dem_server built with MPI (libopenmpi-dev)\n";
  bool mpi = false;
  for (int i = 1; i < argc; ++i) mpi = mpi || std::string_view(argv[i]) == "--mpi";
  if (!mpi) return dfc::protocol::run_server_main(argc, argv, program);
#ifdef DFC_DEM_MPI
  return dfc::dem::run_mpi_server_main(argc, argv, program, [](int processes, int rank) {
    return std::make_unique<dfc::dem::DemBackend>(dfc::dem::make_world_engine, processes, rank);
  });
#else
  std::cerr << "dem_server: --mpi: this dem_server was built without MPI (CMake found none); install libopenmpi-dev and build again, "
               "or run on one process (participants.dem.mpi_ranks 1)\n";
  return 2;
#endif
}
