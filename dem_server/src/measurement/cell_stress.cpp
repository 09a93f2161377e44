#include "dfc/dem/cell_stress.hpp"

#include <algorithm>
#include <numbers>

#include "dfc/common/errors.hpp"
#include "dfc/dem/bond_state.hpp"

namespace dfc::dem {

CellStress measure_cell_stress(const Simulation& sim) {
  if (!sim.periodic_cell()) throw UserError("the cell stress needs a periodic cell");
  const PeriodicCell& cell = *sim.periodic_cell();
  const PeriodicSpace space(cell);
  const ParticleStore& p = sim.particles();
  const PairContacts& pairs = sim.pair_contacts();
  const ContactOutputs& out = sim.contact_outputs();
  double r_max = 0.0;
  for (const double r : p.radius) r_max = std::max(r_max, r);
  const double kn = sim.settings().particle_law.stiffness_bound(r_max).normal;
  // A bond resists the next strain increment whether or not it carries load:
  // one installed with zero load (sample_preparation.hpp) has no force yet but
  // its full stiffness. Counting only the pairs in force gave K_a = 0 right
  // after the installation, and the servo then strained the bonded cell at its
  // cap (1e-4 per step: about E 1e-4 ~ 0.1 MPa of stress in one step, whatever
  // the target), which at a low target overshot it many times and yielded bonds.
  const bool bonded_law = sim.settings().particle_law.bonded() && pairs.stride > 0;
  CellStress s;
  const auto count = std::min(pairs.size(), out.force.size());
  for (std::size_t k = 0; k < count; ++k) {
    const Vec3 f = out.force[k];
    if (f == Vec3{} && !(bonded_law && is_bonded(bond_state(pairs.history.data() + k * pairs.stride)))) continue;
    const Vec3 d = space.branch(p.position[pairs.first[k]], p.position[pairs.second[k]]);
    const double fa[3] = {f.x, f.y, f.z};
    const double da[3] = {d.x, d.y, d.z};
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t b = 0; b < 3; ++b) s.sigma[a][b] -= fa[a] * da[b];
    const double inv_d2 = 1.0 / norm2(d);
    // k_n (d . e_a)^2 n_a^2 = k_n d_a^4 / |d|^2: the normal force change of the
    // contact per unit affine strain along a, times its lever d_a.
    s.affine_stiffness += kn * inv_d2 * Vec3{d.x * d.x * d.x * d.x, d.y * d.y * d.y * d.y, d.z * d.z * d.z * d.z};
  }
  const double inv_v = 1.0 / cell.volume();
  for (auto& row : s.sigma)
    for (auto& v : row) v *= inv_v;
  s.affine_stiffness *= inv_v;
  return s;
}

double cell_porosity(const ParticleStore& particles, const PeriodicCell& cell) {
  return 1.0 - sphere_volume_sum(particles) / cell.volume();
}

}  // namespace dfc::dem
