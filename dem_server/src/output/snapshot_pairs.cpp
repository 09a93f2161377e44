#include "dfc/dem/snapshot_pairs.hpp"

#include <cmath>

#include "dfc/dem/bond_state.hpp"
#include "dfc/dem/damage_bond_law.hpp"
#include "dfc/dem/periodic_cell.hpp"

namespace dfc::dem {

namespace {

/// What one pair carries at the end of the last step, along and across its centre line.
struct PairLoad {
  double normal = 0.0;  ///< N, tension positive
  double shear = 0.0;   ///< N, magnitude
  double gap = 0.0;     ///< m, surface gap
  Vec3 force;           ///< N, on the first sphere
};

class PairLoads {
 public:
  explicit PairLoads(const Simulation& s)
      : p_(s.particles()),
        pairs_(s.pair_contacts()),
        space_(s.periodic_cell() ? PeriodicSpace(*s.periodic_cell()) : PeriodicSpace()),
        // Before the first step, or after one that kept only the gathered
        // outputs, there is no force of every pair to read.
        forces_(s.step_count() > 0 && s.contact_outputs_complete() && s.contact_outputs().force.size() >= s.pair_contacts().size()
                    ? &s.contact_outputs().force
                    : nullptr) {}

  [[nodiscard]] Vec3 branch(std::size_t k) const { return space_.branch(p_.position[pairs_.first[k]], p_.position[pairs_.second[k]]); }

  [[nodiscard]] PairLoad load(std::size_t k) const {
    const Vec3 d = branch(k);
    const double length = norm(d);
    PairLoad out;
    out.gap = length - p_.radius[pairs_.first[k]] - p_.radius[pairs_.second[k]];
    if (forces_ == nullptr || !(length > 0.0)) return out;
    const Vec3 n = (1.0 / length) * d;
    // The force is the one on the first sphere: pulled towards the second
    // (along +n) when the pair is in tension.
    const Vec3& f = (*forces_)[k];
    out.force = f;
    out.normal = dot(f, n);
    out.shear = norm(f - out.normal * n);
    return out;
  }

 private:
  const ParticleStore& p_;
  const PairContacts& pairs_;
  PeriodicSpace space_;
  const std::vector<Vec3>* forces_;
};

}  // namespace

void append_bond_arrays(const Simulation& s, std::vector<protocol::Array>& arrays) {
  const ParticleStore& p = s.particles();
  const PairContacts& pairs = s.pair_contacts();
  const PairLoads loads(s);
  // damage_bond keeps its damage variable D (Ciantia et al. 2024 Eq. 2) in a
  // history column: written per bond as bond_damage (1 once broken).
  const bool has_damage = s.settings().particle_law.info != nullptr && s.settings().particle_law.info->keyword == DamageBondLaw::keyword;
  std::vector<std::int64_t> state, index, id;
  std::vector<double> where, damage, normal, shear, opening;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const double* history = pairs.history.data() + k * pairs.stride;
    const BondState b = bond_state(history);
    if (b == BondState::none) continue;
    const std::uint32_t i = pairs.first[k], j = pairs.second[k];
    const Vec3 at = p.position[i] + (p.radius[i] / (p.radius[i] + p.radius[j])) * loads.branch(k);
    where.insert(where.end(), {at.x, at.y, at.z});
    state.push_back(std::int64_t(b));
    index.insert(index.end(), {std::int64_t(i), std::int64_t(j)});
    id.insert(id.end(), {p.id[i], p.id[j]});
    const PairLoad load = loads.load(k);
    normal.push_back(load.normal);
    shear.push_back(load.shear);
    opening.push_back(load.gap);
    if (has_damage) damage.push_back(is_bonded(b) ? history[DamageBondLaw::damage] : 1.0);
  }
  const auto m = std::int64_t(state.size());
  arrays.push_back(protocol::Array::from_f64("bond_position", {m, 3}, where));
  arrays.push_back(protocol::Array::from_i64("bond_state", {m}, state));
  arrays.push_back(protocol::Array::from_i64("bond_particle_index", {m, 2}, index));
  arrays.push_back(protocol::Array::from_i64("bond_particle_id", {m, 2}, id));
  arrays.push_back(protocol::Array::from_f64("bond_normal_force_n", {m}, normal));
  arrays.push_back(protocol::Array::from_f64("bond_shear_force_n", {m}, shear));
  arrays.push_back(protocol::Array::from_f64("bond_opening_m", {m}, opening));
  if (has_damage) arrays.push_back(protocol::Array::from_f64("bond_damage", {m}, damage));
}

void append_contact_arrays(const Simulation& s, double min_normal_force, std::vector<protocol::Array>& arrays) {
  const PairContacts& pairs = s.pair_contacts();
  const PairLoads loads(s);
  std::vector<std::int64_t> index;
  std::vector<double> normal, force;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    // The neighbour list holds pairs that are near but apart: no force, no contact.
    const PairLoad load = loads.load(k);
    if (load.force == Vec3{} || std::abs(load.normal) < min_normal_force) continue;
    index.insert(index.end(), {std::int64_t(pairs.first[k]), std::int64_t(pairs.second[k])});
    normal.push_back(-load.normal);
    force.insert(force.end(), {load.force.x, load.force.y, load.force.z});
  }
  const auto c = std::int64_t(normal.size());
  arrays.push_back(protocol::Array::from_i64("contact_particle_index", {c, 2}, index));
  arrays.push_back(protocol::Array::from_f64("contact_normal_force_n", {c}, normal));
  arrays.push_back(protocol::Array::from_f64("contact_force_n", {c, 3}, force));
}

}  // namespace dfc::dem
