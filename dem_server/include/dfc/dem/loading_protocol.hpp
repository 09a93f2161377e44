#pragma once
// Loading protocols: what one experiment does to a built DEM model — a pile
// jacked at a velocity, UCS platens, a triaxial test in six walls, the servo of
// a periodic cell — behind one interface. DemBackend's advance, monitors and
// checkpoint and build_model's preparation are loops over the protocols a
// section enables; a new experiment is a class in src/loading/ and a row in
// the registry (loading_protocol.cpp), not a branch in each of them.
//
// Life cycle (build_model, then DemBackend):
//   arrange   before the model exists: moves, sizes or sets moving the walls it
//             drives (ModelLayout; e.g. platens seated on the particles)
//   prepare   the particles and walls are in: its preparation stage
//             (consolidation, confinement in walls) and the references its
//             monitors are measured from
//   advance   before_advance; then on every step before_step, step (at most one
//             protocol replaces the engine's step with a servo-controlled step),
//             after_step; end_advance after the steps; averages over the advance.
//             These hooks get the DemEngine (dem_engine.hpp): on many processes
//             every process runs them alike, and what they read of the
//             particles for the whole body goes through its collectives
//   monitors  its instantaneous monitors at the end of an advance
//   progress  the few of them the coupler shows while the run goes and at its
//             end (SPEC.md §4.2, configure's info.progress_monitors)
//   state     what a checkpoint must keep of it (the rest follows from the section)
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/common/state_archive.hpp"
#include "dfc/dem/dem_engine.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct DemConfig;
struct DemModel;
struct ModelLayout;

/// What a preparation stage needs beyond the model: the final radii of a
/// radius expansion (by particle id; empty without one) and the time-step
/// fraction of the section.
struct PreparationInputs {
  std::span<const double> final_radius;
  double fraction_of_critical = 0.2;
};

/// Sums over the steps of one advance that every protocol may read: the force
/// of the particles on each wall (in Simulation::walls() order), and 1 / steps.
struct AdvanceSums {
  std::span<const Vec3> wall_force;
  double inv_steps = 1.0;
};

class LoadingProtocol {
 public:
  virtual ~LoadingProtocol() = default;

  /// True if prepare() runs a preparation stage after which the bonds are
  /// installed (PFC order); the model then starts without bonds.
  [[nodiscard]] virtual bool prepares_sample() const { return false; }
  virtual void arrange(ModelLayout& layout) { (void)layout; }
  virtual void prepare(DemModel& model, const PreparationInputs& inputs) {
    (void)model;
    (void)inputs;
  }

  /// True if step() replaces the engine's plain step (the section reader lets at most one protocol do so).
  [[nodiscard]] virtual bool drives_step() const { return false; }
  virtual void step(DemEngine& engine, double dt) {
    (void)engine;
    (void)dt;
  }
  virtual void before_advance(const DemEngine& engine, std::int64_t steps) {
    (void)engine;
    (void)steps;
  }
  virtual void before_step(DemEngine& engine) { (void)engine; }
  virtual void after_step(const DemEngine& engine) { (void)engine; }
  virtual void end_advance(DemEngine& engine) { (void)engine; }
  /// Writes its advance-averaged monitors (impulse / duration) into `out` and resets its sums.
  virtual void averages(const DemEngine& engine, const AdvanceSums& sums, nlohmann::json& out) {
    (void)engine;
    (void)sums;
    (void)out;
  }
  /// Adds its instantaneous monitors to `out` (which holds the averages and
  /// the common monitors); fills an averaged one the last advance did not send.
  virtual void monitors(const DemEngine& engine, nlohmann::json& out) const {
    (void)engine;
    (void)out;
  }

  /// Appends to `out` (a JSON array) the monitors the coupler shows on its
  /// progress line and in its summary, as SPEC.md §4.2's info.progress_monitors
  /// entries {monitor, label, scale, unit}.
  virtual void progress_monitors(nlohmann::json& out) const { (void)out; }

  virtual void save_state(StateWriter& out) const { (void)out; }
  virtual void load_state(StateReader& in) { (void)in; }
};

struct LoadingProtocolEntry {
  std::string_view section;  ///< the key of the DEM section that enables it
  /// The protocol of `config`, or null when its section is absent.
  std::unique_ptr<LoadingProtocol> (*make)(const DemConfig& config);
  /// Every monitor it may send, with its unit (SPEC.md §6.3: declaring one a run never sends is allowed).
  void (*declare_monitors)(nlohmann::json& units);
};

/// The protocols, in the order their hooks run: the ones with a preparation
/// stage first, so the others take their references from the prepared model.
[[nodiscard]] std::span<const LoadingProtocolEntry> loading_protocol_registry();

/// The protocols `config` enables, in registry order.
[[nodiscard]] std::vector<std::unique_ptr<LoadingProtocol>> make_loading_protocols(const DemConfig& config);

// The registered protocols (one file each in src/loading/).
[[nodiscard]] std::unique_ptr<LoadingProtocol> make_cell_loading(const DemConfig& config);
[[nodiscard]] std::unique_ptr<LoadingProtocol> make_triaxial_loading(const DemConfig& config);
[[nodiscard]] std::unique_ptr<LoadingProtocol> make_ucs_loading(const DemConfig& config);
[[nodiscard]] std::unique_ptr<LoadingProtocol> make_pile_loading(const DemConfig& config);
void declare_cell_monitors(nlohmann::json& units);
void declare_triaxial_monitors(nlohmann::json& units);
void declare_ucs_monitors(nlohmann::json& units);
void declare_pile_monitors(nlohmann::json& units);

}  // namespace dfc::dem
