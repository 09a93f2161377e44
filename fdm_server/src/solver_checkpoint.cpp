// Solver::save_state / load_state: the FDM's running state as raw bytes
// (protocol/SPEC.md §4.7, docs/checkpoints.md). Stored as they are, so a
// restored solver takes the same steps bit for bit: gridpoint velocities and
// displacements, the loads and masses the coupling set (external forces,
// extra masses, prescribed velocities), the inertial masses of the last Δt,
// tetrahedron stresses, the constitutive models' internal variables, the
// tetrahedron forces of the next step, the monitors and the step count. The
// mesh, material and settings, and what the boundary conditions and initial
// stress of the section set, are checked by size and otherwise rebuilt by
// configure; boundary supports are stored anyway (a coupling may change them).
#include "dfc/fdm/stored_as_bytes.hpp"
#include "dfc/fdm/solver.hpp"

namespace dfc::fdm {

namespace {
// Mirrors Solver's members in declaration order (solver.hpp): a new member
// breaks this assert until it is stored below or named as configuration.
struct SolverLayout {
  Mesh mesh_;
  Material material_;
  SolverSettings settings_;
  std::vector<Tetrahedron> tetrahedra_;
  std::vector<std::size_t> incidence_offsets_, incidence_;
  std::vector<double> real_mass_, mass_scaling_coefficient_, extra_mass_, inertial_mass_;
  double inertial_mass_dt_;
  bool inertial_mass_stale_;
  double critical_timestep_;
  std::vector<Vec3> velocity_, displacement_, body_force_, face_load_, external_force_;
  std::vector<std::array<bool, 3>> fixed_;
  std::vector<Vec3> radial_roller_;
  std::vector<char> prescribed_;
  std::vector<Vec3> prescribed_velocity_;
  std::vector<Stress> stress_;
  std::vector<double> model_state_;
  std::vector<std::array<Vec3, 4>> tet_force_;
  std::vector<double> unbalanced_magnitude_, applied_magnitude_;
  std::vector<Vec3> reaction_;
  Vec3 support_reaction_;
  double unbalanced_force_ratio_, kinetic_energy_;
  std::int64_t step_count_;
};
}  // namespace

static_assert(sizeof(Solver) == sizeof(SolverLayout), "a Solver member is missing from Solver::save_state");

void Solver::save_state(StateWriter& out) const {
  out.tag("fdm solver");
  out.value(mesh_.gridpoint_count());
  out.value(tetrahedra_.size());
  out.vector(extra_mass_);
  out.vector(inertial_mass_);
  out.value(inertial_mass_dt_);
  out.value(inertial_mass_stale_);
  out.vector(velocity_);
  out.vector(displacement_);
  out.vector(face_load_);
  out.vector(external_force_);
  out.vector(fixed_);
  out.vector(radial_roller_);
  out.vector(prescribed_);
  out.vector(prescribed_velocity_);
  out.vector(stress_);
  out.vector(model_state_);
  out.vector(tet_force_);
  out.value(unbalanced_force_ratio_);
  out.value(kinetic_energy_);
  out.value(support_reaction_);
  out.value(step_count_);
}

void Solver::load_state(StateReader& in) {
  in.tag("fdm solver");
  const auto gridpoints = in.value<std::size_t>();
  const auto tetrahedra = in.value<std::size_t>();
  if (gridpoints != mesh_.gridpoint_count() || tetrahedra != tetrahedra_.size())
    in.fail("a grid of " + std::to_string(mesh_.gridpoint_count()) + " gridpoints and " + std::to_string(tetrahedra_.size()) +
            " tetrahedra as configured (the checkpoint has " + std::to_string(gridpoints) + " and " + std::to_string(tetrahedra) + ")");
  const std::size_t state_size = model_state_.size();
  in.vector(extra_mass_);
  in.vector(inertial_mass_);
  in.value(inertial_mass_dt_);
  in.value(inertial_mass_stale_);
  in.vector(velocity_);
  in.vector(displacement_);
  in.vector(face_load_);
  in.vector(external_force_);
  in.vector(fixed_);
  in.vector(radial_roller_);
  in.vector(prescribed_);
  in.vector(prescribed_velocity_);
  in.vector(stress_);
  in.vector(model_state_);
  in.vector(tet_force_);
  in.value(unbalanced_force_ratio_);
  in.value(kinetic_energy_);
  in.value(support_reaction_);
  in.value(step_count_);
  for (const std::size_t size : {extra_mass_.size(), velocity_.size(), displacement_.size(), face_load_.size(), external_force_.size(),
                                 fixed_.size(), radial_roller_.size(), prescribed_.size(), prescribed_velocity_.size()})
    if (size != gridpoints) in.fail("gridpoint arrays of " + std::to_string(gridpoints) + " entries");
  if (stress_.size() != tetrahedra || tet_force_.size() != tetrahedra || model_state_.size() != state_size)
    in.fail("tetrahedron arrays of " + std::to_string(tetrahedra) + " entries and the configured model's internal variables");
}

}  // namespace dfc::fdm
