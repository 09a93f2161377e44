#pragma once
// The axisymmetric updated-Lagrangian explicit solver (docs/continuum_pile.md
// §1–§3, §6): linear triangles on the current geometry, the rate of
// deformation with its hoop term, the Jaumann rotation, the volumetric strain
// increment from a nodal pressure field (Dohrmann–Bochev projection by
// default), any shared constitutive model (dfc_constitutive), central
// differences with scaled masses (Δt = 1) and local damping as in fdm_server
// (theory/fdm.md §1.8–§1.11), and optionally pore water at the nodes (Biot,
// explicit Darcy flow).
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "dfc/constitutive/constitutive_model.hpp"
#include "dfc/continuum/axisymmetric_mesh.hpp"
#include "dfc/continuum/delaunay_retriangulation.hpp"
#include "dfc/continuum/pore_water.hpp"
#include "dfc/continuum/pressure_projection.hpp"
#include "dfc/continuum/rigid_pile.hpp"
#include "dfc/continuum/triangle_kinematics.hpp"

namespace dfc::continuum {

enum class VolumetricStrain {
  /// Each triangle its own (constant-strain triangles: lock as ν → 0.5).
  element,
  /// Bonet & Burton's (1998) average nodal volumetric strain.
  nodal_average,
  /// Dohrmann & Bochev's (2004) stabilised nodal pressure (pressure_projection.hpp).
  pressure_projection,
};

struct SolverSettings {
  /// Local damping coefficient α (Cundall 1987; theory/fdm.md §1.9).
  double damping = 0.8;
  /// Scaled mass = safety × ¼ × the Gershgorin row sum of the stiffness
  /// (Δt = 1 is stable for safety ≥ 1 on a fixed geometry); the margin covers
  /// the coupling added by the nodal averaging and the stiffening of
  /// elements between two steps.
  double mass_safety = 2.0;
  /// How a triangle's volumetric strain increment is formed
  /// (docs/continuum_pile.md §3): the Dohrmann & Bochev (2004) pressure
  /// projection by default. `nodal_average` is cheaper and, where the
  /// pressure gradient is steep (a plastic zone), a little closer, but
  /// carries a pressure checkerboard as ν → 0.5; `element` locks.
  VolumetricStrain volumetric_strain = VolumetricStrain::pressure_projection;
  /// Factor on the projection's weight τ = K/G (Dohrmann & Bochev 2004 use 1).
  double pressure_stabilisation = 1.0;
  /// Pore water (u–p_w, docs/continuum_pile.md §6); off by default (drained).
  PoreWaterSettings pore_water;
  /// Density at the start, kg/m³: each triangle's mass ρ V₀ is kept (mass
  /// balance of an updated-Lagrangian element) and carried across remeshes.
  double density = 1000.0;
};

/// What a remesh did (docs/continuum_pile.md §4–§5).
struct RemeshReport {
  Index triangles_before = 0;
  Index triangles_after = 0;
  /// New triangles that were not triangles of the old mesh.
  Index triangles_changed = 0;
  /// Nodes added by the Delaunay refinement.
  Index nodes_added = 0;
  double mass_before = 0.0;  ///< kg
  /// Σ ρ V of the new triangles with the transferred densities, before the
  /// correction that restores mass_before exactly, kg.
  double mass_transferred = 0.0;
  /// Corrections of the transferred stresses towards the old nodal forces
  /// (docs/continuum_pile.md §5), each followed by the model's return.
  int equilibrium_iterations = 0;
  /// The nodal force mismatch (norm, N) the last correction removed: below
  /// 1e-6 of the internal forces' norm unless the iterations ran out.
  double equilibrium_residual = 0.0;
};

enum class Axis { r = 0, z = 1 };

class AxisymmetricSolver {
 public:
  /// Every triangle starts at `initial_stress` with the model's initial history for it.
  AxisymmetricSolver(AxisymmetricMesh mesh, std::shared_ptr<const constitutive::ConstitutiveModel> model,
                     const Stress& initial_stress, SolverSettings settings = {});

  /// Holds the pore pressure of the nodes at `pressure` (Pa, compression
  /// positive) from now on: a drained boundary. Requires pore water.
  void prescribe_pore_pressure(std::span<const Index> nodes, double pressure);
  /// The flow's time per mechanical step, s (0: undrained): changeable between steps.
  void set_flow_time_per_step(double seconds) { settings_.pore_water.time_per_step = seconds; }
  /// Holds the velocity component of the nodes at `velocity` (m per step) from now on.
  void prescribe_velocity(std::span<const Index> nodes, Axis axis, double velocity);
  /// A normal pressure (Pa, compression positive) on the edges of `edge_group`,
  /// applied on the current geometry each step.
  void apply_pressure(const std::string& edge_group, double pressure);

  /// Puts the rigid pile in contact with every node of the soil
  /// (docs/continuum_pile.md §6; rigid_pile.hpp); it moves with each step.
  void set_pile(const RigidPile& pile) { pile_ = pile; }
  [[nodiscard]] bool has_pile() const { return pile_.has_value(); }
  /// The pile (set_pile first); its velocity may be changed between steps.
  [[nodiscard]] RigidPile& pile() { return pile_.value(); }
  [[nodiscard]] const RigidPile& pile() const { return pile_.value(); }
  /// Per node, its contact with the pile in the last step.
  [[nodiscard]] std::span<const NodeContact> pile_contacts() const { return pile_contacts_; }
  /// The soil's force on the pile per face in the last step, N.
  [[nodiscard]] PileForces pile_forces() const { return RigidPile::forces_on_pile(pile_contacts_); }

  /// One step of Δt = 1 (pseudo-time).
  void step();

  [[nodiscard]] const AxisymmetricMesh& mesh() const { return mesh_; }
  /// Nodal velocities, m per step (the displacement of the coming step).
  [[nodiscard]] std::span<const Point> velocities() const { return velocities_; }
  /// ½ Σ m v² of the scaled masses (v in m per step): a measure of the
  /// pseudo-dynamic motion that dies out in equilibrium, not a physical energy.
  [[nodiscard]] double kinetic_energy() const;
  /// Effective stresses σ′ of the triangles (Pa, tension positive); equal to
  /// the total stresses without pore water.
  [[nodiscard]] std::span<const Stress> stresses() const { return stresses_; }
  /// Pore pressure per node, Pa, compression positive (zeros without pore water).
  [[nodiscard]] std::span<const double> pore_pressures() const { return pore_pressures_; }
  /// Total stress of triangle t: σ = σ′ − α p̄_w I, p̄_w its nodes' mean.
  [[nodiscard]] Stress total_stress(Index triangle) const;
  /// Time the flow has advanced, s.
  [[nodiscard]] double flow_time() const { return flow_time_; }
  /// Flow substeps of the last step (docs/continuum_pile.md §6).
  [[nodiscard]] int flow_substeps() const { return flow_substeps_; }

  /// Sum over `nodes` of the internal nodal forces of the last step (N): for
  /// nodes whose motion is prescribed, the force the body resists it with.
  [[nodiscard]] Point internal_force_sum(std::span<const Index> nodes) const;
  /// Mean unbalanced force magnitude of the free components over the mean
  /// magnitude of the internal and applied forces (theory/fdm.md §1.11), of
  /// the last step or, after a remesh, of the new mesh.
  [[nodiscard]] double unbalanced_force_ratio() const { return unbalanced_force_ratio_; }
  /// The smallest triangle area over its value when the triangle was created (detects inversion).
  [[nodiscard]] double smallest_area_ratio() const;
  /// The smallest angle of any triangle, degrees: when to remesh.
  [[nodiscard]] double smallest_angle_deg() const;
  [[nodiscard]] long steps_taken() const { return steps_; }
  /// Σ of the triangles' masses, kg.
  [[nodiscard]] double total_mass() const;

  /// Re-triangulates the current nodes (constrained Delaunay, the boundary
  /// kept). Each new triangle takes the stress, history and density of the
  /// old triangle containing its centroid, corrected by the change of the
  /// field recovered at the nodes (volume-weighted means) between the two
  /// centroids (limited to the old values around that triangle), so a
  /// triangle that was already there keeps its state. The stresses of the
  /// new triangles and their neighbours are then corrected until every node
  /// has the out-of-balance force it had before (a body in equilibrium stays
  /// in it, the pile's contact force included), alternating the smallest
  /// correction with the model's return to its yield surface
  /// (equilibrium_correction.hpp). The masses are scaled so that the total
  /// is unchanged. Nodes, velocities
  /// and boundary conditions are untouched. With `minimum_angle_deg` > 0 the
  /// triangulation is refined until no angle is smaller (CGAL Delaunay
  /// refinement); an added node takes the old mesh's velocity field, and one
  /// on a boundary edge the velocity components prescribed at both its ends
  /// (interpolated) and the named groups of both, its edge being split in
  /// the edge groups. Pore pressures stay at the nodes; an added node takes
  /// the old mesh's field, and one on an edge whose ends are both drained
  /// (held) is held at their interpolated pressure.
  RemeshReport remesh(double minimum_angle_deg = 0.0);

 private:
  void move_and_update_stresses();
  /// Throws std::runtime_error naming the triangle whose constitutive update
  /// gave a non-finite stress, where it is, its stress and strain increment.
  [[noreturn]] void throw_failed_update(Index triangle, const Stress& before, const SymTensor& strain_increment) const;
  void compute_forces_and_masses();
  void update_velocities();
  /// Adds the pile's contact forces to the external forces (rigid_pile.hpp).
  void apply_pile_contact();
  /// Per triangle, its value of a volumetric field (the strain increment,
  /// the plastic mean-stress change) as the volumetric treatment forms it.
  [[nodiscard]] std::vector<double> volumetric_field(std::span<const double> volumes, std::span<const double> values);
  /// The flow of the step's time (explicit Darcy, subcycled; docs/continuum_pile.md §6).
  void advance_flow();
  /// The pore water's stabilised storage C + τ_w S (docs/continuum_pile.md §6).
  [[nodiscard]] ProjectionOperator water_operator() const;
  /// K + α² M_w (the undrained bulk modulus; K without pore water), Pa.
  [[nodiscard]] double undrained_bulk_modulus() const;
  /// Where an added node lies in the old mesh: its triangle and barycentric weights.
  struct Interpolation {
    Index triangle = 0;
    std::array<double, 3> weights{};
  };
  /// Appends the refinement's nodes with their nodal fields, conditions and groups.
  std::vector<Interpolation> add_nodes(const Retriangulation& retriangulation, std::span<const Edge> boundary);
  [[nodiscard]] double measure_unbalanced_force_ratio() const;
  /// Sets triangle t's stress to `stress` returned to the model's yield
  /// surface by a zero-strain update (its history updated with it); false,
  /// and nothing changed, where that update fails.
  bool admit_stress(Index triangle, Stress stress);
  /// After a remesh: corrects the stresses of the `adjustable` triangles
  /// until every node's out-of-balance force is `unbalanced_before` again,
  /// alternating NodalForceCorrection with admit_stress (docs/continuum_pile.md §5).
  void restore_equilibrium(std::span<const Point> unbalanced_before, std::vector<bool> adjustable, RemeshReport& report);

  AxisymmetricMesh mesh_;
  std::shared_ptr<const constitutive::ConstitutiveModel> model_;
  SolverSettings settings_;
  std::vector<Point> velocities_;
  std::vector<Point> internal_forces_;
  std::vector<Point> external_forces_;
  std::vector<double> masses_;
  std::vector<Stress> stresses_;
  std::vector<double> model_state_;
  std::vector<double> initial_areas_;  ///< area of each triangle when it was created
  std::vector<double> triangle_masses_;  ///< kg
  /// Per node and axis: whether the velocity is prescribed, and its value.
  std::vector<std::array<bool, 2>> prescribed_;
  std::vector<Point> prescribed_velocities_;
  std::vector<std::pair<std::string, double>> pressures_;
  PressureProjection projection_;        ///< the skeleton's nodal volumetric strain
  PressureProjection water_projection_;  ///< the pore water's pressure change
  std::vector<double> pore_pressures_;
  std::vector<bool> pore_pressure_prescribed_;
  std::optional<RigidPile> pile_;
  std::vector<NodeContact> pile_contacts_;
  double flow_time_ = 0.0;
  int flow_substeps_ = 0;
  double unbalanced_force_ratio_ = 0.0;
  long steps_ = 0;
};

}  // namespace dfc::continuum
