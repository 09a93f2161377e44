#pragma once
// Solver: the FLAC3D-style explicit Lagrangian cycle, small strain
// (docs/theory/fdm.md §1.1, §1.12 "Small strain": geometry stays at its initial values).
//
// One step(Δt) is
//   1. gridpoint pass: net force F = Σ tetrahedron forces + ρgV/4 body force +
//      face loads + external forces; unbalanced-force ratio (§1.11); local
//      damping F − α|F|sgn(v) with the previous half-step velocity (§1.9);
//      v += Δt F/m (§1.8); boundary conditions; u += Δt v;
//   2. zone pass: strain rate from the new velocities (§1.4), mixed
//      discretization (§1.5), Δε = ξΔt, constitutive update per tetrahedron
//      (§1.6), for models with plastic volume change the stress pass of mixed
//      discretization (zone-averaged mean-stress increment, §1.5 last
//      paragraph; docs/fdm_models.md §2 #9), tetrahedron nodal forces for the
//      next step (§1.7).
// Running the zone pass last keeps stress, forces and displacements at the same
// time level between steps (what a coupled partner reads); the cycle is that of
// §1.1 started at step 5.
//
// Determinism: tetrahedron forces are stored per tetrahedron and gathered per
// gridpoint in a fixed order, so results are bit-identical for any thread count.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dfc/fdm/boundary_conditions.hpp"
#include "dfc/constitutive/constitutive_model.hpp"
#include "dfc/fdm/mesh.hpp"
#include "dfc/fdm/tetrahedron.hpp"

namespace dfc {
class StateWriter;
class StateReader;
}  // namespace dfc

namespace dfc::fdm {

struct Material {
  double density = 0.0;  ///< kg/m³
  std::unique_ptr<constitutive::ConstitutiveModel> model;
};

struct SolverSettings {
  Vec3 gravity = Vec3::Zero();  ///< m/s², total acceleration (N·g in a centrifuge)
  double local_damping = 0.8;   ///< α of §1.9, in [0, 1)
  /// §1.10 "Static": inertial masses scaled so that any Δt is stable. The mass is
  /// never below the real lumped mass, so for Δt <= critical the dynamics are real.
  bool mass_scaling = true;
  int threads = 0;  ///< OpenMP threads for both passes; 0 = the OpenMP default
};

class Solver {
 public:
  /// Checks the mesh (dfc::UserError on inverted zones) and the material.
  Solver(Mesh mesh, Material material, SolverSettings settings);

  // Set-up ------------------------------------------------------------------
  /// Throws dfc::UserError for an unknown group or a roller on a group that is
  /// neither an axis-aligned plane nor a cylinder about z.
  void apply_boundary_condition(const BoundaryCondition& condition);
  /// Sets every tetrahedron of each zone to `stress_at(zone centroid)`: with
  /// uniform zone stress and lumped gravity this is the discrete equilibrium of
  /// a layered column (§2(c): "the zone stress at the centroid … is ρ g d_c exactly").
  void set_initial_stress(const std::function<Stress(const Vec3& zone_centroid)>& stress_at);

  // Coupling ----------------------------------------------------------------
  /// External force ON gridpoint `gp`, N; stays until changed.
  void set_external_force(Index gp, const Vec3& force);
  /// Extra inertial mass at `gp` (e.g. the partner body's mass), kg; stays until changed.
  void set_extra_mass(Index gp, double mass);
  /// Holds the velocity of `gp` at `velocity` (all components) from the next step on.
  void prescribe_velocity(Index gp, const Vec3& velocity);
  /// `v` with the components that the fixed and roller conditions of `gp` hold
  /// at zero removed (an orthogonal projection onto the free directions). A
  /// static solver on the same mesh uses it to apply the same supports.
  [[nodiscard]] Vec3 constrained(Index gp, Vec3 v) const;
  /// Zeroes all gridpoint velocities and displacements, keeping stresses and
  /// model history (FLAC's "initialize displacement 0" after an equilibrium
  /// stage, so that later displacements are those of the next stage).
  void reset_kinematics();

  // Stepping ----------------------------------------------------------------
  /// Largest stable Δt with real masses, Δt_crit/2 of §1.10.
  [[nodiscard]] double critical_timestep() const { return critical_timestep_; }
  /// Why Δt cannot be run stably (it exceeds critical_timestep() without mass
  /// scaling), or nothing when it can.
  [[nodiscard]] std::optional<std::string> unstable_step_reason(double dt) const;
  /// One cycle. Throws dfc::SolverError when Δt exceeds critical_timestep()
  /// without mass scaling, or when the state becomes non-finite.
  void step(double dt);

  // State -------------------------------------------------------------------
  [[nodiscard]] const Mesh& mesh() const { return mesh_; }
  [[nodiscard]] const SolverSettings& settings() const { return settings_; }
  [[nodiscard]] double density() const { return material_.density; }
  [[nodiscard]] const constitutive::ConstitutiveModel& model() const { return *material_.model; }
  [[nodiscard]] std::span<const Tetrahedron> tetrahedra() const { return tetrahedra_; }
  [[nodiscard]] std::span<const Vec3> velocities() const { return velocity_; }
  [[nodiscard]] std::span<const Vec3> displacements() const { return displacement_; }
  /// The forces set by set_external_force (the coupling's), N, per gridpoint.
  [[nodiscard]] std::span<const Vec3> external_forces() const { return external_force_; }
  [[nodiscard]] std::span<const Stress> tetrahedron_stresses() const { return stress_; }
  /// The constitutive model's history of tetrahedron `tet` (model().state_names() order).
  [[nodiscard]] std::span<const double> tetrahedron_state(Index tet) const;
  /// Volume average of the zone's 10 tetrahedron stresses (§1.6).
  [[nodiscard]] Stress zone_stress(Index zone) const;
  /// Force this body exerts on gridpoint `gp` in its current state: tetrahedron
  /// forces + body force + face loads (no external force), N.
  [[nodiscard]] Vec3 force_exerted_on_gridpoint(Index gp) const;
  /// Real lumped mass, kg (§1.10 dynamic).
  [[nodiscard]] double real_mass(Index gp) const { return real_mass_[gp]; }
  /// Inertial mass used with step `dt`, without extra mass, kg.
  [[nodiscard]] double inertial_mass(Index gp, double dt) const;
  /// Average unbalanced-force ratio of the last step (§1.11); 0 before the first step.
  [[nodiscard]] double unbalanced_force_ratio() const { return unbalanced_force_ratio_; }
  /// ½ Σ m v² with the real masses after the last step, J.
  [[nodiscard]] double kinetic_energy() const { return kinetic_energy_; }
  /// Force the supports exert on the grid in the last step, N: at every held
  /// component (fixed, roller, prescribed velocity) the part of the
  /// gridpoint's net force it cancels, reversed. With the body force and the
  /// coupling's external forces it closes the grid's force balance (the
  /// whole-model weight balance, docs/dem_generation.md §5).
  [[nodiscard]] const Vec3& support_reaction() const { return support_reaction_; }
  /// Σ ρ g V over the grid (the body forces of gravity), N.
  [[nodiscard]] Vec3 total_body_force() const;
  [[nodiscard]] std::int64_t step_count() const { return step_count_; }

  // Checkpoint (solver_checkpoint.cpp) --------------------------------------
  /// Every member that changes while the solver runs or is coupled, as raw bytes.
  void save_state(StateWriter& out) const;
  /// Replaces the running state by save_state()'s of a solver built from the
  /// same mesh, material and settings. Throws StateFormatError when they differ.
  void load_state(StateReader& in);

 private:
  struct GridpointForces {
    Vec3 net;          // tetrahedra + body + loads + external
    double magnitude;  // Σ of the magnitudes of the contributions (§1.11 "applied force")
  };
  [[nodiscard]] Vec3 gathered_tetrahedron_force(Index gp) const;
  [[nodiscard]] GridpointForces gridpoint_forces(Index gp) const;
  void update_inertial_masses(double dt);
  void gridpoint_pass(double dt);
  void zone_pass(double dt);
  void compute_tetrahedron_forces(Index tet);
  void check_finite() const;
  [[nodiscard]] int thread_count() const;

  Mesh mesh_;
  Material material_;
  SolverSettings settings_;
  std::vector<Tetrahedron> tetrahedra_;  // kTetrahedraPerZone per zone, zone-major
  // Gridpoint → (tetrahedron, local node) incidences in CSR form, ascending tetrahedron order.
  std::vector<std::size_t> incidence_offsets_;
  std::vector<std::size_t> incidence_;  // 4 * tet + local node

  std::vector<double> real_mass_;
  std::vector<double> mass_scaling_coefficient_;
  std::vector<double> extra_mass_;
  std::vector<double> inertial_mass_;  // for inertial_mass_dt_, incl. extra mass
  double inertial_mass_dt_ = -1.0;
  bool inertial_mass_stale_ = true;
  double critical_timestep_ = 0.0;

  std::vector<Vec3> velocity_;
  std::vector<Vec3> displacement_;
  std::vector<Vec3> body_force_;      // ρ g V/4 per tetrahedron node, halved per overlay
  std::vector<Vec3> face_load_;       // pressure/traction conditions
  std::vector<Vec3> external_force_;  // set by the coupler

  std::vector<std::array<bool, 3>> fixed_;  // component held at zero
  std::vector<Vec3> radial_roller_;         // unit radial direction, or zero if none
  std::vector<char> prescribed_;
  std::vector<Vec3> prescribed_velocity_;

  std::vector<Stress> stress_;                // per tetrahedron
  std::vector<double> model_state_;           // state_size() per tetrahedron
  std::vector<std::array<Vec3, 4>> tet_force_;  // overlay-weighted nodal forces per tetrahedron

  std::vector<double> unbalanced_magnitude_;  // scratch per gridpoint, summed in fixed order
  std::vector<double> applied_magnitude_;
  std::vector<Vec3> reaction_;  // scratch per gridpoint: the supports' force, summed in fixed order
  Vec3 support_reaction_ = Vec3::Zero();
  double unbalanced_force_ratio_ = 0.0;
  double kinetic_energy_ = 0.0;
  std::int64_t step_count_ = 0;
};

}  // namespace dfc::fdm
