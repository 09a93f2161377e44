#include "dfc/dem/snapshot_pairs.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

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

double id_bits(std::int64_t id) { return std::bit_cast<double>(id); }
std::int64_t id_of(double bits) { return std::bit_cast<std::int64_t>(bits); }

/// Whether pair k is written by this process: its first particle is owned.
bool written_here(const PairContacts& pairs, std::span<const std::uint8_t> owned, std::size_t k) {
  return owned.empty() || owned[pairs.first[k]] != 0;
}

}  // namespace

bool bond_damage_written(const Simulation& s) {
  // damage_bond keeps its damage variable D (Ciantia et al. 2024 Eq. 2) in a
  // history column: written per bond as bond_damage (1 once broken).
  return s.settings().particle_law.info != nullptr && s.settings().particle_law.info->keyword == DamageBondLaw::keyword;
}

PairRows bond_rows(const Simulation& s, std::span<const std::uint8_t> owned) {
  const ParticleStore& p = s.particles();
  const PairContacts& pairs = s.pair_contacts();
  const PairLoads loads(s);
  const bool with_damage = bond_damage_written(s);
  PairRows rows{.width = with_damage ? 10U : 9U, .values = {}};
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const double* history = pairs.history.data() + k * pairs.stride;
    const BondState b = bond_state(history);
    if (b == BondState::none || !written_here(pairs, owned, k)) continue;
    const std::uint32_t i = pairs.first[k], j = pairs.second[k];
    const Vec3 at = p.position[i] + (p.radius[i] / (p.radius[i] + p.radius[j])) * loads.branch(k);
    const PairLoad load = loads.load(k);
    rows.values.insert(rows.values.end(), {id_bits(p.id[i]), id_bits(p.id[j]), double(b), at.x, at.y, at.z, load.normal, load.shear, load.gap});
    if (with_damage) rows.values.push_back(is_bonded(b) ? history[DamageBondLaw::damage] : 1.0);
  }
  return rows;
}

PairRows contact_rows(const Simulation& s, double min_normal_force, std::span<const std::uint8_t> owned) {
  const ParticleStore& p = s.particles();
  const PairContacts& pairs = s.pair_contacts();
  const PairLoads loads(s);
  PairRows rows{.width = 6, .values = {}};
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (!written_here(pairs, owned, k)) continue;
    // The neighbour list holds pairs that are near but apart: no force, no contact.
    const PairLoad load = loads.load(k);
    if (load.force == Vec3{} || std::abs(load.normal) < min_normal_force) continue;
    rows.values.insert(rows.values.end(),
                       {id_bits(p.id[pairs.first[k]]), id_bits(p.id[pairs.second[k]]), -load.normal, load.force.x, load.force.y, load.force.z});
  }
  return rows;
}

void sort_by_ids(PairRows& rows) {
  const std::size_t n = rows.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto key = [&](std::size_t r) { return std::pair(id_of(rows.values[r * rows.width]), id_of(rows.values[r * rows.width + 1])); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  std::vector<double> sorted;
  sorted.reserve(rows.values.size());
  for (const std::size_t r : order)
    sorted.insert(sorted.end(), rows.values.begin() + std::ptrdiff_t(r * rows.width), rows.values.begin() + std::ptrdiff_t((r + 1) * rows.width));
  rows.values = std::move(sorted);
}

ParticleRows::ParticleRows(std::span<const std::int64_t> ids) {
  by_id_.reserve(ids.size());
  for (std::size_t row = 0; row < ids.size(); ++row) by_id_.emplace_back(ids[row], std::int64_t(row));
  std::sort(by_id_.begin(), by_id_.end());
}

std::int64_t ParticleRows::operator()(std::int64_t id) const {
  const auto it = std::lower_bound(by_id_.begin(), by_id_.end(), std::pair(id, std::int64_t{0}));
  if (it == by_id_.end() || it->first != id) throw std::logic_error("snapshot pair of particle id " + std::to_string(id) + " that the snapshot does not hold");
  return it->second;
}

void append_bond_arrays(const PairRows& rows, const ParticleRows& rows_of, bool with_damage, std::vector<protocol::Array>& arrays) {
  std::vector<std::int64_t> state, index, id;
  std::vector<double> where, damage, normal, shear, opening;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const double* row = rows.values.data() + r * rows.width;
    const std::int64_t a = id_of(row[0]), b = id_of(row[1]);
    id.insert(id.end(), {a, b});
    index.insert(index.end(), {rows_of(a), rows_of(b)});
    state.push_back(std::int64_t(row[2]));
    where.insert(where.end(), {row[3], row[4], row[5]});
    normal.push_back(row[6]);
    shear.push_back(row[7]);
    opening.push_back(row[8]);
    if (with_damage) damage.push_back(row[9]);
  }
  const auto m = std::int64_t(state.size());
  arrays.push_back(protocol::Array::from_f64("bond_position", {m, 3}, where));
  arrays.push_back(protocol::Array::from_i64("bond_state", {m}, state));
  arrays.push_back(protocol::Array::from_i64("bond_particle_index", {m, 2}, index));
  arrays.push_back(protocol::Array::from_i64("bond_particle_id", {m, 2}, id));
  arrays.push_back(protocol::Array::from_f64("bond_normal_force_n", {m}, normal));
  arrays.push_back(protocol::Array::from_f64("bond_shear_force_n", {m}, shear));
  arrays.push_back(protocol::Array::from_f64("bond_opening_m", {m}, opening));
  if (with_damage) arrays.push_back(protocol::Array::from_f64("bond_damage", {m}, damage));
}

void append_contact_arrays(const PairRows& rows, const ParticleRows& rows_of, std::vector<protocol::Array>& arrays) {
  std::vector<std::int64_t> index;
  std::vector<double> normal, force;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const double* row = rows.values.data() + r * rows.width;
    index.insert(index.end(), {rows_of(id_of(row[0])), rows_of(id_of(row[1]))});
    normal.push_back(row[2]);
    force.insert(force.end(), {row[3], row[4], row[5]});
  }
  const auto c = std::int64_t(normal.size());
  arrays.push_back(protocol::Array::from_i64("contact_particle_index", {c, 2}, index));
  arrays.push_back(protocol::Array::from_f64("contact_normal_force_n", {c}, normal));
  arrays.push_back(protocol::Array::from_f64("contact_force_n", {c, 3}, force));
}

void append_bond_arrays(const Simulation& s, std::vector<protocol::Array>& arrays) {
  append_bond_arrays(bond_rows(s, {}), ParticleRows(s.particles().id), bond_damage_written(s), arrays);
}

void append_contact_arrays(const Simulation& s, double min_normal_force, std::vector<protocol::Array>& arrays) {
  append_contact_arrays(contact_rows(s, min_normal_force, {}), ParticleRows(s.particles().id), arrays);
}

}  // namespace dfc::dem
