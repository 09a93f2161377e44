// dem_mpi_throughput: the real workload's speed on MPI processes
// (DistributedSimulation, docs/determinism.md §3); bench/mpi_scaling.sh runs it.
//
//   mpiexec -n P dem_mpi_throughput --section FILE [--threads T] [--warmup N] [--steps N] [--rebuild-every N]
//
// FILE is a DEM section as dem_server receives it (bench/paper_model.sh and
// bench/mpi_scaling.sh write them from scenarios/open_pile_chalk.json). Every
// process builds the model (generation included) and runs --warmup steps
// alone, alike (the first step's seam balance solves over the whole body);
// then rank 0's body is decomposed over the P processes and --steps steps are
// timed. Rank 0 prints one line: particle-steps/s, the share of the time in
// the halo updates (waits for the slowest process included) and in the
// decompositions, the load imbalance (max/mean owned particles), the halo
// (particles held for others, and bytes sent per step, summed over processes),
// and a digest of the final state gathered by id: the same for any P.
// --rebuild-every N decomposes the body again before every N-th timed step,
// as a run whose particles move half the skin every N steps (the paper run
// rebuilds about every 270 steps, docs/dem_benchmarks.md): a body at rest
// alone would never show the cost of a decomposition.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

#include <mpi.h>
#include <nlohmann/json.hpp>

#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/distributed_simulation.hpp"
#include "dfc/dem/model_builder.hpp"

namespace {

using namespace dfc::dem;

struct Options {
  std::string section;
  int threads = 1;
  int warmup = 20;
  int steps = 200;
  int rebuild_every = 0;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << "usage: mpiexec -n P dem_mpi_throughput --section FILE [--threads T] [--warmup N] [--steps N] [--rebuild-every N]\n"
                   "The DEM section FILE decomposed over P processes of T threads: particle-steps/s, the halo's and\n"
                   "the decompositions' share of the time, load imbalance, halo size and bytes, and a state digest\n"
                   "(the same for any P and T). bench/mpi_scaling.sh runs it on 1..P processes.\n";
      std::exit(0);
    }
    if (i + 1 >= argc) throw std::runtime_error("option " + a + " needs a value (--help)");
    const std::string v = argv[++i];
    if (a == "--section") o.section = v;
    else if (a == "--threads") o.threads = std::stoi(v);
    else if (a == "--warmup") o.warmup = std::stoi(v);
    else if (a == "--steps") o.steps = std::stoi(v);
    else if (a == "--rebuild-every") o.rebuild_every = std::stoi(v);
    else throw std::runtime_error("unknown option " + a + " (--help)");
  }
  if (o.section.empty()) throw std::runtime_error("--section FILE is required (--help)");
  return o;
}

/// FNV-1a over the bits of every particle's motion and loads, by id.
std::uint64_t digest(const std::vector<ParticleRecord>& particles) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const ParticleRecord& r : particles) {
    const Vec3 fields[5] = {r.position, r.velocity, r.angular_velocity, r.force, r.moment};
    const auto* bytes = reinterpret_cast<const unsigned char*>(fields);
    for (std::size_t b = 0; b < sizeof(fields); ++b) hash = (hash ^ bytes[b]) * 1099511628211ull;
    const auto* id = reinterpret_cast<const unsigned char*>(&r.id);
    for (std::size_t b = 0; b < sizeof(r.id); ++b) hash = (hash ^ id[b]) * 1099511628211ull;
  }
  return hash;
}

double max_over(double value, MPI_Op op) {
  double out = 0.0;
  MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, op, MPI_COMM_WORLD);
  return out;
}

void run(const Options& o) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  std::ifstream in(o.section);
  if (!in) throw std::runtime_error("cannot read " + o.section);
  nlohmann::json section = nlohmann::json::parse(in);
  section["threads"] = o.threads;
  DemModel model = build_model(parse_dem_config(section));
  Simulation& sim = *model.simulation;
  for (int s = 0; s < o.warmup; ++s) sim.step(model.dt);
  DistributedSimulation body(MPI_COMM_WORLD, sim);
  body.step(model.dt);  // the first decomposition, untimed
  const DecompositionStats before = body.stats();
  MPI_Barrier(MPI_COMM_WORLD);
  const auto t0 = std::chrono::steady_clock::now();
  for (int s = 0; s < o.steps; ++s) {
    if (o.rebuild_every > 0 && s % o.rebuild_every == 0) body.request_rebuild();
    body.step(model.dt);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const DecompositionStats& after = body.stats();
  const double owned = double(after.owned), halo = double(after.halo), bytes = double(after.halo_bytes_per_step);
  const double total = max_over(owned, MPI_SUM), most = max_over(owned, MPI_MAX);
  const double halo_total = max_over(halo, MPI_SUM), bytes_total = max_over(bytes, MPI_SUM);
  const double halo_share = max_over((after.halo_seconds - before.halo_seconds) / seconds, MPI_MAX);
  const double decompose_share = max_over((after.decompose_seconds - before.decompose_seconds) / seconds, MPI_MAX);
  const auto particles = body.gather_particles(0);
  if (rank != 0) return;
  std::cout << "ranks " << ranks << " threads " << o.threads << ": " << total * o.steps / seconds << " particle-steps/s (" << seconds << " s for "
            << o.steps << " steps of " << total << " particles, dt " << model.dt << " s, " << after.decompositions - before.decompositions
            << " decompositions; halo share " << halo_share << ", decomposition share " << decompose_share << ", imbalance "
            << most / (total / ranks) << ", halo " << halo_total << " particles (" << halo_total / total << " per owned), " << bytes_total
            << " bytes per step; state digest " << std::hex << digest(particles) << std::dec << ")" << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int status = 0;
  try {
    run(parse(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "dem_mpi_throughput: " << e.what() << std::endl;
    status = 1;
  }
  MPI_Finalize();
  return status;
}
