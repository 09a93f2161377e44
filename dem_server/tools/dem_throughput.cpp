// dem_throughput: time the DEM hot loop on a settled bed (particle-steps/s).
//
//   dem_throughput [--side N] [--layers N] [--threads "1 2"] [--steps N] [--max-settle N]
//   dem_throughput --data FILE [--threads "1 2"] [--warmup 1000] [--steps 2000] [--law linear|linear_pbond|damage_bond]
//                  [--local-damping A]
//   dem_throughput --section FILE [--threads "1 2"] [--warmup N] [--steps N] [--digest] [--rebuild-every N]
//
// --section: the real workload. FILE is a DEM section as dem_server receives
// it (gravity_m_s2 included; bench/paper_model.sh writes one from a scenario):
// the model is built as the server builds it (generation, pile, walls) once per
// thread count, --warmup steps run untimed from the generated state, then
// --steps timed. Prints particle-steps/s, pair candidates and bonds per
// particle at the first and last timed step, and the resident memory per
// particle; --digest hashes the final state (the same at every thread count).
// --rebuild-every N rebuilds the neighbour lists before every N-th timed step
// (as a run whose particles move by half the skin every N steps): the rebuild's
// cost is the difference to the rate without it.
//
// --law linear_pbond: the same packing with every pair closer than 10 um
// bonded by a linear parallel bond as stiff as the contact and too strong to
// break (the bonded throughput of issue 3; the peers' README lists LAMMPS BPM
// with every contact bonded). Its linear part is the same contact: k_n =
// pi E* R^2/(2R) = 1e5 N/m for the mean pair (R = 0.55 mm) gives E* = 1.157e8 Pa.
// --law damage_bond: the same bonds by the damage-bond law (the chalk of the
// studies), as stiff, with strengths too high to reach (1e15 Pa): intact
// bonds only, so the law's own cost per bond sets the difference to
// linear_pbond (while intact its linear contact is off, dem_contact_laws.md §3.6).
// --local-damping A: PFC's local damping on the particles (the studies use 0.7).
//
// --data: the peer benchmark (shared/bench/peers/README.md) on a LAMMPS data
// file (atom_style sphere: id type diameter density x y z): kn 1e5 N/m,
// ks 2/7 kn, mu 0.5, dt 1e-6 s, skin 0.11 mm, no local damping, periodic in x
// and y, floor at z = 0; read at rest, --warmup steps untimed, then --steps
// timed. Differences from the peers (docs/dem_benchmarks.md): both
// dashpots are fractions of critical, beta_n = 0.215 and beta_s = 0.2015, which
// match the peers' gamma_n = 1.418e5 1/s and gamma_t = gamma_n / 2 for the mean
// pair (m_eff = 9.2e-7 kg) but not exactly for the others; the shear dashpot is
// cut while a contact slides. The kinetic energy after 600 steps is within
// 0.3 % of LAMMPS's (bench/dem_peers.sh prints the check).
//
// 1. builds a bed of N x N x layers spheres (r 4.5-5 mm, rho 2650, linear law
//    kn 1e5 N/m, ks kn/4, mu 0.5, beta_n 0.3) in a box with a frictional floor
//    and frictionless sides, and settles it under gravity with local damping
//    0.7 until the unbalanced-force ratio falls below 1e-4 (or --max-settle steps);
// 2. for each thread count, restarts the settled bed and times --steps steps.
// Throughput = particles x steps / wall seconds, the measure of the peer
// benchmark (shared/bench/peers/README.md). Without --data the bed is not the
// peers' packing (a walled box, larger spheres): compare orders of magnitude
// only; --data runs their packing and model.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <numbers>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "dfc/common/command_line.hpp"
#include "dfc/common/version.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/model_builder.hpp"

namespace {

using namespace dfc::dem;

struct Options {
  int side = 20;
  int layers = 8;
  std::vector<int> threads{1, 2};
  int steps = 2000;
  int max_settle = 400000;
  std::string data;  ///< LAMMPS data file: the peer benchmark instead of the settled bed
  int warmup = 1000;
  std::string law = "linear";  ///< --data only: "linear", "linear_pbond" or "damage_bond"
  double local_damping = 0.0;  ///< --data only: local damping coefficient
  std::string section;         ///< DEM section file: the real workload instead of a packing
  bool digest = false;         ///< --data, --section: print a hash of the final state's bits
  int rebuild_every = 0;       ///< --section: rebuild the lists before every N-th timed step (0: only when due)
  std::string perf_control;    ///< --section: "CTL_FIFO,ACK_FIFO" of a `perf record --control`, enabled for the timed steps only
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << "dem_throughput: time the DEM hot loop (particle-steps/s)\n\n"
                   "  dem_throughput [--side N] [--layers N] [--threads \"1 2\"] [--steps N] [--max-settle N]\n"
                   "  dem_throughput --data FILE [--threads \"1 2\"] [--warmup 1000] [--steps 2000]\n"
                   "                 [--law linear|linear_pbond|damage_bond] [--local-damping A] [--digest]\n"
                   "  dem_throughput --section FILE [--threads \"1 2\"] [--warmup N] [--steps N] [--digest]\n"
                   "                 [--rebuild-every N] [--perf-control CTL_FIFO,ACK_FIFO]\n\n"
                   "Without --data: settles a bed of N x N x layers spheres, then times --steps steps per thread count.\n"
                   "With --data: the peer benchmark on a LAMMPS data file (the PEERS_DIR folder of bench/dem_peers.sh);\n"
                   "damage_bond bonds every pair within 10 um by the damage-bond law, too strong to yield.\n"
                   "With --section: a DEM section as dem_server receives it (bench/paper_model.sh writes one from a\n"
                   "scenario), built once per thread count; prints the rate, pairs and bonds per particle, memory;\n"
                   "--rebuild-every N rebuilds the neighbour lists before every N-th timed step (the rebuild's cost).\n"
                   "--perf-control: the two FIFOs of `perf record -D -1 --control fifo:CTL,ACK`: the profile is enabled\n"
                   "for the timed steps only, not for building the model (bench/paper_model.sh, PROFILE=1).\n"
                   "--digest: also print a hash of the final state's bits (positions, velocities, spins, resultants,\n"
                   "pair history, contact forces), to check that a change to the code leaves results bit-identical.\n";
      std::exit(0);
    }
    if (a == "--version") {
      std::cout << "dem_throughput " << dfc::project_version() << "\n";
      std::exit(0);
    }
  }
  for (int i = 1; i < argc; i += 2) {
    if (std::string(argv[i]) == "--digest") {
      o.digest = true;
      --i;
      continue;
    }
    if (i + 1 >= argc) throw std::runtime_error(std::string("option ") + argv[i] + " needs a value");
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--side") o.side = int(dfc::parse_count_option(a, v, 2, 1000));
    else if (a == "--layers") o.layers = int(dfc::parse_count_option(a, v, 1, 1000));
    else if (a == "--steps") o.steps = int(dfc::parse_count_option(a, v, 1, 1000000000));
    else if (a == "--max-settle") o.max_settle = int(dfc::parse_count_option(a, v, 0, 1000000000));
    else if (a == "--data") o.data = v;
    else if (a == "--warmup") o.warmup = int(dfc::parse_count_option(a, v, 0, 1000000000));
    else if (a == "--law") {
      if (v != "linear" && v != "linear_pbond" && v != "damage_bond")
        throw std::runtime_error("--law must be linear, linear_pbond or damage_bond, not " + v);
      o.law = v;
    }
    else if (a == "--local-damping") o.local_damping = dfc::parse_number_option(a, v, dfc::Bounds{0.0, 1.0});
    else if (a == "--section") o.section = v;
    else if (a == "--rebuild-every") o.rebuild_every = int(dfc::parse_count_option(a, v, 0, 1000000000));
    else if (a == "--perf-control") {
      if (v.find(',') == std::string::npos) throw std::runtime_error("--perf-control takes CTL_FIFO,ACK_FIFO (the FIFOs of perf record --control)");
      o.perf_control = v;
    }
    else if (a == "--threads") {
      o.threads.clear();
      std::istringstream list(v);
      for (std::string t; list >> t;) o.threads.push_back(int(dfc::parse_count_option(a, t, 1, 4096)));
      if (o.threads.empty()) throw std::runtime_error("--threads takes one or more thread counts, as \"1 2\"");
    } else throw std::runtime_error("unknown option " + a);
  }
  if (o.digest && o.data.empty() && o.section.empty()) throw std::runtime_error("--digest needs --data or --section (it hashes their final state)");
  if (!o.data.empty() && !o.section.empty()) throw std::runtime_error("--data and --section are two benchmarks: give one");
  if (!o.perf_control.empty() && o.section.empty()) throw std::runtime_error("--perf-control needs --section (it profiles the timed steps of a section)");
  return o;
}

nlohmann::json bed(const Options& o, int threads) {
  const double pitch = 2 * 0.005 * 1.05, side = o.side * pitch, height = o.layers * pitch;
  const nlohmann::json smooth = {{"kn_n_m", 1e5}, {"ks_n_m", 2.5e4}, {"friction", 0.0}, {"damping_ratio_normal", 0.3}};
  nlohmann::json walls = nlohmann::json::array({{{"type", "plane"}, {"name", "floor"}, {"point_m", {0.5 * side, 0.5 * side, 0}}, {"normal", {0, 0, 1}}}});
  for (const auto& [point, normal] : {std::pair<std::vector<double>, std::vector<double>>{{0, 0.5 * side, 0}, {1, 0, 0}},
                                      {{side, 0.5 * side, 0}, {-1, 0, 0}}, {{0.5 * side, 0, 0}, {0, 1, 0}}, {{0.5 * side, side, 0}, {0, -1, 0}}})
    walls.push_back({{"type", "plane"}, {"point_m", point}, {"normal", normal}, {"contact", smooth}});
  return {{"particles",
           {{"generator", "lattice"},
            {"region", {{"type", "box"}, {"min_m", {0, 0, 0}}, {"max_m", {side, side, height}}}},
            {"radius_min_m", 0.0045},
            {"radius_max_m", 0.005},
            {"density_kg_m3", 2650}}},
          {"contact", {{"kn_n_m", 1e5}, {"ks_n_m", 2.5e4}, {"friction", 0.5}, {"damping_ratio_normal", 0.3}}},
          {"timestep", {{"fraction_of_critical", 0.3}}},
          {"gravity_m_s2", {0, 0, -9.81}},
          {"walls", walls},
          {"threads", threads}};
}

/// The peer packing: box bounds and spheres [x, y, z, r] of a LAMMPS data file (atom_style sphere).
struct PeerPacking {
  double box[3][2] = {};
  nlohmann::json spheres = nlohmann::json::array();
};

PeerPacking read_lammps_data(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  PeerPacking pack;
  std::string line;
  bool atoms = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    if (!atoms) {
      double lo = 0, hi = 0;
      std::string a, b;
      if (words >> lo >> hi >> a >> b) {
        const int axis = a == "xlo" ? 0 : a == "ylo" ? 1 : a == "zlo" ? 2 : -1;
        if (axis >= 0) pack.box[axis][0] = lo, pack.box[axis][1] = hi;
      }
      atoms = line.rfind("Atoms", 0) == 0;
      continue;
    }
    if (line.rfind("Velocities", 0) == 0) break;  // the section after Atoms
    long id = 0, type = 0;
    double diameter = 0, density = 0, x = 0, y = 0, z = 0;
    if (words >> id >> type >> diameter >> density >> x >> y >> z) pack.spheres.push_back({x, y, z, 0.5 * diameter});
  }
  if (pack.spheres.empty()) throw std::runtime_error(path + " holds no \"Atoms # sphere\" section");
  return pack;
}

/// The peers' contact; "linear_pbond": the same contact with an unbreakable bond on every pair within 10 um of touching.
/// Dashpots as fractions of critical, beta = m_eff gamma / (2 sqrt(m_eff k)) for the
/// mean pair (d 1.1 mm, 2650 kg/m3, m_eff 9.23e-7 kg): gamma_n 1.418e5 1/s with k_n
/// gives 0.215, gamma_t = gamma_n / 2 with k_t = 2/7 k_n gives 0.2015.
nlohmann::json peer_law(const std::string& law) {
  if (law == "linear")
    return {{"kn_n_m", 1e5}, {"ks_n_m", 1e5 * 2.0 / 7.0}, {"friction", 0.5}, {"damping_ratio_normal", 0.215}, {"damping_ratio_shear", 0.2015}};
  const double emod = 1e5 / (std::numbers::pi * 0.55e-3 / 2.0);
  if (law == "damage_bond")
    return {{"law", "damage_bond"}, {"emod_pa", emod}, {"kratio", 3.5}, {"friction", 0.5}, {"damping_ratio_normal", 0.215},
            {"damping_ratio_shear", 0.2015}, {"bond_emod_pa", emod}, {"bond_kratio", 3.5}, {"ten_pa", 1e15}, {"com_pa", 1e15},
            {"coh_pa", 1e15}, {"ucn_m", 1e-5}, {"ucs_m", 1e-5}, {"theta_c_rad", 1e-2}, {"bond_gap_m", 1e-5}};
  return {{"law", "linear_pbond"}, {"emod_pa", emod},  {"kratio", 3.5},       {"friction", 0.5},      {"damping_ratio_normal", 0.215},
          {"pb_emod_pa", emod},    {"pb_kratio", 3.5}, {"pb_ten_pa", 1e15}, {"pb_coh_pa", 1e15}, {"bond_gap_m", 1e-5}, {"damping_ratio_shear", 0.2015}};
}

nlohmann::json peer_scenario(const PeerPacking& pack, int threads, const std::string& law_name, double local_damping) {
  const nlohmann::json law = peer_law(law_name);
  // Periodic in x and y like the peers (docs/dem_periodic.md), with their
  // floor at z = 0: the settled packing rests its bottom layer up to 31 nm into
  // it (a contact, not a cut: model_builder.cpp keeps such spheres).
  const double floor_z = 0.0;
  const double xc = 0.5 * (pack.box[0][0] + pack.box[0][1]), yc = 0.5 * (pack.box[1][0] + pack.box[1][1]);
  const double half = (pack.box[0][1] - pack.box[0][0]) + (pack.box[1][1] - pack.box[1][0]);  // covers the cell and its images
  const nlohmann::json walls = nlohmann::json::array({{{"type", "plane"}, {"name", "floor"}, {"point_m", {xc, yc, floor_z}}, {"normal", {0, 0, 1}}, {"half_size_m", half}}});
  const nlohmann::json periodic = {{"min_m", {pack.box[0][0], pack.box[1][0], floor_z}},
                                   {"max_m", {pack.box[0][1], pack.box[1][1], pack.box[2][1]}},
                                   {"axes", "xy"}};
  return {{"particles", {{"generator", "list"}, {"spheres", pack.spheres}, {"density_kg_m3", 2650}}},
          {"contact", law},
          {"wall_contact", peer_law("linear")},
          {"damping", {{"local", local_damping}}},
          {"timestep", {{"dt_s", 1e-6}}},
          {"gravity_m_s2", {0, 0, -9.81}},
          {"neighbour", {{"skin_m", 1.1e-4}}},
          {"walls", walls},
          {"periodic", periodic},
          {"threads", threads}};
}

/// FNV-1a over the bits of the state a change must leave bit-identical.
std::uint64_t state_digest(const Simulation& sim) {
  std::uint64_t hash = 14695981039346656037ull;
  const auto add = [&hash](const auto& values) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
    for (std::size_t b = 0; b < values.size() * sizeof(values[0]); ++b) hash = (hash ^ bytes[b]) * 1099511628211ull;
  };
  const ParticleStore& p = sim.particles();
  add(p.position);
  add(p.velocity);
  add(p.angular_velocity);
  add(p.force);
  add(p.moment);
  // Whole rows (hot then cold columns, contact_model.hpp SplitsHistory): the
  // values, whatever arrays hold them.
  const PairContacts& pairs = sim.pair_contacts();
  std::vector<double> row(pairs.whole_stride());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    pairs.copy_whole_row(k, row.data());
    add(row);
  }
  add(sim.contact_outputs().force);
  return hash;
}

/// Sum of m v^2 / 2: what the peers' README reports (LAMMPS's thermo `ke`,
/// LIGGGHTS's `ke` column), unlike Measurements::kinetic_energy, which adds the spins.
double translational_kinetic_energy(const ParticleStore& p) {
  double energy = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) energy += 0.5 * p.mass[i] * norm2(p.velocity[i]);
  return energy;
}

/// The peer benchmark protocol on a data file: warm-up untimed, then timed.
void run_peer_benchmark(const Options& o) {
  const PeerPacking pack = read_lammps_data(o.data);
  for (const int threads : o.threads) {
    DemModel model = build_model(parse_dem_config(peer_scenario(pack, threads, o.law, o.local_damping)));
    Simulation& sim = *model.simulation;
    if (model.removed_particles > 0) std::cout << model.removed_particles << " spheres cut by the side walls were removed\n";
    sim.run(o.warmup, 1e-6);
    const std::size_t rebuilds = sim.rebuild_count();
    const auto t0 = std::chrono::steady_clock::now();
    sim.run(o.steps, 1e-6);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const Measurements m = measure(sim);
    std::cout << "threads " << sim.threads() << ": " << double(sim.particles().size()) * o.steps / seconds << " particle-steps/s ("
              << seconds << " s for " << o.steps << " steps of " << sim.particles().size() << " particles, " << sim.rebuild_count() - rebuilds
              << " rebuilds, " << sim.pair_contacts().size() << " pair candidates, coordination " << m.coordination_number << ", kinetic energy "
              << m.kinetic_energy << " J (translational " << translational_kinetic_energy(sim.particles()) << " J)";
    if (sim.settings().particle_law.bonded()) std::cout << ", bonds intact " << sim.bond_counts().intact;
    if (o.digest) std::cout << ", state digest " << std::hex << state_digest(sim) << std::dec;
    std::cout << ")\n";
  }
}

/// kB of a "Vm...:" line of /proc/self/status (0 where there is none).
double status_kilobytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind(field + ":", 0) == 0) return std::stod(line.substr(field.size() + 1));
  return 0.0;
}

/// Where the resident memory is: bytes the program holds in allocations, and
/// bytes the allocator keeps freed but unreturned (glibc's mallinfo2; "" on
/// other C libraries). Tells a model's own arrays from what generation left.
std::string allocator_report() {
#if defined(__GLIBC__)
  const struct mallinfo2 heap = mallinfo2();
  std::ostringstream out;
  out << "; allocations " << double(heap.uordblks + heap.hblkhd) / 1e9 << " GB, freed and kept by the allocator " << double(heap.fordblks) / 1e9
      << " GB";
  return out.str();
#else
  return "";
#endif
}

/// Pair candidates and bonds that hold (intact or damaged), each per particle.
std::string pairs_and_bonds(const Simulation& sim) {
  const double n = double(sim.particles().size());
  const BondCounts b = sim.bond_counts();
  std::ostringstream out;
  out << double(sim.pair_contacts().size()) / n << " pair candidates and " << double(b.intact + b.damaged) / n << " bonds per particle";
  return out.str();
}

/// A `perf record --control fifo:CTL,ACK` session started disabled (-D -1):
/// enable() and disable() send the commands and wait for perf's "ack", so
/// that the profile holds the timed steps and nothing of the model's build
/// (the paper model's generation takes longer than its steps).
class PerfWindow {
 public:
  explicit PerfWindow(const std::string& fifos) {
    if (fifos.empty()) return;
    const auto comma = fifos.find(',');
    control_.open(fifos.substr(0, comma));
    ack_.open(fifos.substr(comma + 1));
    if (!control_ || !ack_) throw std::runtime_error("--perf-control: cannot open the FIFOs " + fifos + " (start perf record --control first)");
  }
  void enable() { send("enable"); }
  void disable() { send("disable"); }

 private:
  void send(const char* command) {
    if (!control_.is_open()) return;
    control_ << command << std::endl;
    std::string reply;
    if (!std::getline(ack_, reply) || reply.find("ack") == std::string::npos)
      throw std::runtime_error(std::string("--perf-control: perf did not acknowledge ") + command + " (it answered '" + reply + "', stream " + (ack_.eof() ? "at end" : "open") + ")");
  }
  std::ofstream control_;
  std::ifstream ack_;
};

/// The serial work a coupled run adds outside Simulation::step, on one
/// thread whatever the thread count (dem_backend.cpp): every step the damping
/// force total (a monitor), every advance the monitors (measure, momentum,
/// bond counts). Returns "X ms per step, Y ms per advance", the best of three.
std::string serial_monitor_cost(const Simulation& sim) {
  const auto best_of_three = [](const auto& work) {
    double best = 1e300;
    for (int round = 0; round < 3; ++round) {
      const auto t0 = std::chrono::steady_clock::now();
      work();
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return best;
  };
  volatile double sink = 0.0;  // keeps the sums from being optimised away
  const double per_step = best_of_three([&] { sink = sink + sim.damping_force_total().x; });
  const double per_advance = best_of_three([&] {
    const Measurements m = measure(sim);
    const BondCounts b = sim.bond_counts();
    sink = sink + m.kinetic_energy + sim.momentum().x + double(b.intact);
  });
  std::ostringstream out;
  out << per_step * 1e3 << " ms per step (damping total), " << per_advance * 1e3 << " ms per advance (measure, momentum, bond counts)";
  return out.str();
}

/// The real workload: a DEM section built as dem_server builds it, stepped at rest.
void run_section_benchmark(const Options& o) {
  std::ifstream in(o.section);
  if (!in) throw std::runtime_error("cannot read " + o.section);
  const nlohmann::json section = nlohmann::json::parse(in);
  PerfWindow profile(o.perf_control);
  for (const int threads : o.threads) {
    nlohmann::json with_threads = section;
    with_threads["threads"] = threads;
    const auto built = std::chrono::steady_clock::now();
    DemModel model = build_model(parse_dem_config(with_threads));
    Simulation& sim = *model.simulation;
    const double build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count();
    sim.run(o.warmup, model.dt);
    const double rss = status_kilobytes("VmRSS") * 1024.0;
    const std::string heap = allocator_report();
    const std::string first = pairs_and_bonds(sim);
    const std::size_t rebuilds = sim.rebuild_count();
    profile.enable();
    const auto t0 = std::chrono::steady_clock::now();
    if (o.rebuild_every > 0) {
      for (int done = 0; done < o.steps; done += o.rebuild_every) {
        static_cast<void>(sim.particles_for_edit());  // marks the lists stale: the next step rebuilds them
        sim.run(std::min(o.rebuild_every, o.steps - done), model.dt);
      }
    } else {
      sim.run(o.steps, model.dt);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    profile.disable();
    const double n = double(sim.particles().size());
    std::cout << "threads " << sim.threads() << ": " << n * o.steps / seconds << " particle-steps/s (" << seconds << " s for " << o.steps
              << " steps of " << sim.particles().size() << " particles, dt " << model.dt << " s, " << sim.rebuild_count() - rebuilds
              << " rebuilds; first step " << first << ", last " << pairs_and_bonds(sim) << "; resident memory " << rss / n
              << " bytes per particle (" << rss / 1e9 << " GB, peak " << status_kilobytes("VmHWM") * 1024.0 / 1e9 << " GB" << heap << "); built in "
              << build_seconds << " s; serial work of a coupled run outside the step: " << serial_monitor_cost(sim);
    if (o.digest) std::cout << ", state digest " << std::hex << state_digest(sim) << std::dec;
    std::cout << ")" << std::endl;
  }
}

}  // namespace

int main(int argc, char** argv) try {
  const Options o = parse(argc, argv);
  if (!o.data.empty()) {
    run_peer_benchmark(o);
    return 0;
  }
  if (!o.section.empty()) {
    run_section_benchmark(o);
    return 0;
  }
  // 1. Settle.
  DemModel model = build_model(parse_dem_config(bed(o, 0)));
  Simulation& settling = *model.simulation;
  std::int64_t settle_steps = 0;
  double ratio = 1.0;
  while (settle_steps < o.max_settle && ratio > 1e-4) {
    settling.run(5000, model.dt);
    settle_steps += 5000;
    ratio = measure(settling).unbalanced_force_ratio;
  }
  const Measurements settled = measure(settling);
  std::cout << settled.particle_count << " particles settled in " << settle_steps << " steps: unbalanced force ratio " << ratio
            << ", coordination number " << settled.coordination_number << ", candidate pairs per particle "
            << double(settling.pair_contacts().size()) / double(settled.particle_count) << "\n";

  // 2. Time each thread count from the same settled state.
  for (const int threads : o.threads) {
    DemModel timed = build_model(parse_dem_config(bed(o, threads)));
    Simulation& sim = *timed.simulation;
    ParticleStore& p = sim.particles_for_edit();
    p = settling.particles();  // settled positions and velocities (contact history restarts)
    sim.run(200, model.dt);    // rebuild the lists, reload the shear springs
    const std::size_t rebuilds = sim.rebuild_count();
    const auto t0 = std::chrono::steady_clock::now();
    sim.run(o.steps, model.dt);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << "threads " << sim.threads() << ": " << double(p.size()) * o.steps / seconds << " particle-steps/s (" << seconds << " s for "
              << o.steps << " steps, " << sim.rebuild_count() - rebuilds << " rebuilds)\n";
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "dem_throughput: " << e.what() << "\n";
  return 1;
}
