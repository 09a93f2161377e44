#pragma once
// DemBackend: the DEM as a protocol v1 server (SPEC.md §4–§6, docs/theory/coupling.md).
//
// Coupling (accepts_interface): set_interface turns the continuum's boundary
// nodes and facets into the coupling wall "interface"; each advance takes the
// node velocities, moves the wall with them for n steps, and returns the force
// the particles exert ON each node, averaged over the n steps (impulse /
// duration, the steps being equal).
//
// Sign conventions: forces are the force ON the named body (SPEC §6.2).
//   force                      particles on interface nodes, N
//   interface_force_reaction   sum of forces the interface exerted ON the particles,
//                              summed from the particle side (= -sum(force))
//   interface_power_w          sum over nodes of force . velocity (power into the continuum)
//   pile_displacement_m        pile travel along its velocity direction (positive = penetration)
//   pile_force_n               force of the particles on the pile along -velocity direction
//                              (positive = resisting penetration), averaged over the advance
//   pile_peak_force_n          the largest pile_force_n of any advance so far (kept in a checkpoint)
//   pile_tip_force_n, pile_shaft_force_n  its part on the flat end's facets and on the others
//   pile_inner_shaft_force_n, pile_outer_shaft_force_n  an open tube's (pile.wall_thickness_m) shaft
//                              parts, each from its facets (the tip is then the annulus)
//   pile_plug_length_m, pile_plug_particles  an open tube's soil column above its tip (pile_plug.hpp)
//   pile_inertial_number       I = (v/D) d / sqrt(p_tip/rho_s) of the push, 0 at rest (inertial_number.hpp)
//   wall_<name>_force_n/_moment_nm  particles on each rigid wall (moment about the origin), averaged
//   axial_stress_pa, axial_strain   with a "ucs" section only (ucs_platens.hpp): platen stress,
//                              compression positive, averaged over the advance; strain at its end
//   cell_stress_xx/yy/zz_pa    with a "periodic" cell only (cell_stress.hpp): Love–Weber stress,
//                              compression positive, averaged over the advance
//   cell_strain_xx/yy/zz       engineering strain of the cell edges from the end of preparation,
//                              (L0 - L)/L0, compression positive, at the end of the advance
//   porosity                   1 - sphere volume / cell (or triaxial box) volume
//   axial_stress_pa, lateral_stress_pa, deviatoric_stress_pa, axial_strain, volumetric_strain
//                              with a "triaxial" section (triaxial_walls.hpp): platen stress, mean
//                              lateral wall stress and their difference (averaged over the advance),
//                              (H0 - H)/H0 and (V0 - V)/V0 from the end of the confinement
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dfc/dem/dem_config.hpp"
#include "dfc/dem/dem_engine.hpp"
#include "dfc/dem/model_builder.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::dem {

class DemBackend final : public protocol::SolverBackend {
 public:
  /// `make_engine` makes the engine of each configured model (dem_engine.hpp)
  /// over `processes` processes, this one being `rank`: a LocalEngine on one,
  /// or under MPI a DistributedEngine in every process's DemBackend
  /// (dem_server --mpi, where every process runs the same requests and rank 0
  /// speaks the protocol: mpi_server.hpp).
  explicit DemBackend(std::function<std::unique_ptr<DemEngine>(Simulation&)> make_engine = make_local_engine, int processes = 1, int rank = 0);
  [[nodiscard]] protocol::SolverIdentity identity() const override;
  nlohmann::json configure(const nlohmann::json& section) override;
  void set_interface(const protocol::InterfaceMesh& mesh) override;
  protocol::AdvanceResult advance(const protocol::AdvanceRequest& request) override;
  [[nodiscard]] nlohmann::json monitors() override;
  [[nodiscard]] std::vector<protocol::Array> snapshot(std::string& kind) override;
  /// Capability checkpoint (dem_checkpoint.cpp): the simulation's running state and the last advance's averages.
  [[nodiscard]] std::string checkpoint_state() override;
  void restore_state(std::string_view bytes) override;

  /// The model (tests, tools): this process's part of it. Throws ProtocolError(out_of_order) before configure.
  [[nodiscard]] const Simulation& simulation() const;

 private:
  Simulation& sim();
  /// The model's engine, made at its first use after configure and set_interface (which may still remove spheres).
  DemEngine& engine();
  /// The particle arrays of a snapshot of a body on many processes: gathered by id on rank 0.
  [[nodiscard]] std::vector<protocol::Array> gathered_snapshot();
  /// configure's info.monitor_units (SPEC.md §6.3): the unit of every monitor monitors() may send.
  [[nodiscard]] nlohmann::json monitor_units() const;

  std::function<std::unique_ptr<DemEngine>(Simulation&)> make_engine_;
  int processes_ = 1;
  int rank_ = 0;  ///< 0 writes the backend's lines on stderr
  DemConfig config_;
  DemModel model_;
  std::unique_ptr<DemEngine> engine_;  ///< over model_.simulation; null until first used
  std::optional<std::size_t> interface_wall_;
  std::size_t generation_removed_by_interface_ = 0;  ///< generated spheres the coupling wall cut (set_interface)
  LoadingProtocol* stepper_ = nullptr;        ///< the protocol whose step replaces Simulation::step (none: the plain step)
  nlohmann::json averages_ = nlohmann::json::object();  ///< advance-averaged monitors of the last advance
};

}  // namespace dfc::dem
