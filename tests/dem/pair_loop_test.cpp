// The pair loop (contact_kernels.hpp evaluate_pair_contacts) against the law
// applied contact by contact.
//
// The loop classifies candidates in blocks, writes the idle ones first, and
// evaluates the acting ones in stages (all kinematics, then all in-plane
// history rotations, then the law). None of that may change a result: every
// contact's force, couple and history must be, bit for bit, what the law's
// own evaluate(kinematics, history) gives for that contact alone, with the
// kinematics of the documented convention (normal from the first centre to
// the second, contact point in the middle of the overlap, velocities of the
// material points there). The chain below has more candidates than a block
// (256) and more acting pairs than a stage (64), and mixes overlapping,
// gap-bonded, broken and separated pairs, so every path of the loop runs.
// In the periodic variant every second sphere sits one cell edge away, so
// half the pairs meet through the boundary (minimum image, image shift,
// lever arm of the image) and the cell deforms (affine relative velocity);
// the particle sums the loop adds are checked too.
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "dfc/common/sections/dem_sections.hpp"
#include "dfc/dem/contact_kernels.hpp"
#include "dfc/dem/damage_bond_law.hpp"
#include "dfc/dem/linear_law.hpp"
#include "dfc/dem/linear_pbond_law.hpp"
#include "dfc/dem/particle_loads.hpp"
#include "dfc/dem/periodic_cell.hpp"

namespace dfc::dem {
namespace {

constexpr std::size_t sphere_count = 700;
constexpr double radius = 1e-3;
constexpr double dt = 1e-6;

/// A jittered chain along x: pair (k, k+1) overlaps, sits in a small gap or is
/// apart; random velocities and spins. Every odd sphere is moved by
/// `odd_offset` (a cell edge: the pair then meets through the boundary).
ParticleStore jittered_chain(std::mt19937_64& rng, const Vec3& odd_offset) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  ParticleStore p;
  double x = 0.0;
  for (std::size_t s = 0; s < sphere_count; ++s) {
    const double r = radius * (1.0 + 0.1 * unit(rng));
    if (s > 0) x += p.radius[s - 1] + r + 0.04 * radius * unit(rng);  // surface gap in [-4 %, 4 %] of R
    const Vec3 offset = s % 2 == 1 ? odd_offset : Vec3{};
    p.add_sphere(std::int64_t(s), Vec3{x, 0.05 * radius * unit(rng), 0.05 * radius * unit(rng)} + offset, r, 2650.0);
    p.velocity[s] = {0.01 * unit(rng), 0.01 * unit(rng), 0.01 * unit(rng)};
    p.angular_velocity[s] = {10.0 * unit(rng), 10.0 * unit(rng), 10.0 * unit(rng)};
  }
  p.force.assign(p.size(), Vec3{});
  p.moment.assign(p.size(), Vec3{});
  return p;
}

/// Candidates (k, k+1) with history rows of random values, in-plane vectors
/// not in the current plane (the loop must rotate them); `prepare` sets
/// law-specific columns (e.g. the bond state).
template <class Law, class Prepare>
PairContacts chain_pairs(const Law& law, const ParticleStore& p, std::mt19937_64& rng, const Prepare& prepare) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PairContacts pairs;
  pairs.set_strides(Law::history_size, cold_history_size_of<Law>());
  for (std::uint32_t s = 0; s + 1 < p.size(); ++s) {
    pairs.first.push_back(s);
    pairs.second.push_back(s + 1);
  }
  pairs.resize_history();
  std::vector<double> whole(Law::history_size);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    for (double& v : whole) v = 1e-3 * unit(rng);
    prepare(k, whole.data());
    pairs.set_whole_row(k, whole.data());
  }
  compute_pair_constants(law, p, pairs);
  return pairs;
}

/// One contact evaluated alone, with its kinematics built here from the
/// convention, and where the loop must have put its loads.
struct AloneResult {
  ContactForce force;
  Vec3 point;
  Vec3 shift;      ///< image offset of the second particle (periodic)
  Vec3 arm_second; ///< lever arm of the force on the second particle
};

template <class Law, class Space>
AloneResult evaluate_alone(const Law& law, const ParticleStore& p, std::uint32_t i, std::uint32_t j, double* history, const Space& space) {
  const Vec3 xi = p.position[i];
  const Vec3 d = space.branch(xi, p.position[j]);
  // j's image next to i (j itself in open space).
  const Vec3 xj = Space::periodic ? xi + d : p.position[j];
  AloneResult r;
  if constexpr (Space::periodic) r.shift = (xi + d) - p.position[j];
  const double dist = std::sqrt(norm2(d));
  ContactKinematics kin;
  kin.normal = (1.0 / dist) * d;
  kin.overlap = (p.radius[i] + p.radius[j]) - dist;
  r.point = xi + (p.radius[i] - 0.5 * kin.overlap) * kin.normal;
  const Vec3 vi = p.velocity[i] + cross(p.angular_velocity[i], r.point - xi);
  const Vec3 vj = p.velocity[j] + cross(p.angular_velocity[j], r.point - xj);
  kin.relative_velocity = vj - vi;
  if constexpr (Space::periodic) kin.relative_velocity += space.affine_velocity(d);
  kin.relative_angular_velocity = p.angular_velocity[j] - p.angular_velocity[i];
  kin.mean_spin_about_normal = mean_spin_about_normal(p.angular_velocity[i], p.angular_velocity[j], kin.normal);
  kin.effective_mass = p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
  kin.radius_first = p.radius[i];
  kin.radius_second = p.radius[j];
  kin.dt = dt;
  r.arm_second = r.point - (p.position[j] + r.shift);
  if (kin.overlap <= 0.0 && !Law::acts_across_gap) {
    law.separate(history);
    return r;
  }
  r.force = law.evaluate(kin, history);
  return r;
}

/// Runs one pair-loop step over the chain and compares every contact with
/// evaluate_alone. Returns the pairs after the step.
template <class Law, class Prepare, class Space = OpenSpace>
PairContacts expect_loop_equals_law_alone(const Law& law, const Prepare& prepare, const Vec3& odd_offset = {}, const Space& space = {}) {
  std::mt19937_64 rng(20261123);
  ParticleStore p = jittered_chain(rng, odd_offset);
  PairContacts pairs = chain_pairs(law, p, rng, prepare);
  // Whole rows (hot then cold columns), as evaluate_alone's law.evaluate takes them.
  std::vector<double> expected_history(pairs.size() * pairs.whole_stride());
  for (std::size_t k = 0; k < pairs.size(); ++k) pairs.copy_whole_row(k, expected_history.data() + k * pairs.whole_stride());
  const Incidence incidence = build_incidence(p.size(), pairs, {}, {}, 1);
  ContactOutputs out;
  out.resize(pairs.size(), Law::has_couple, Space::periodic ? pairs.size() : 0);
  evaluate_pair_contacts(law, p, pairs, incidence, out, dt, ContactRecord::complete, sections::kDefaultMaxOverlapFraction, 1, space);

  std::vector<Vec3> expected_force(p.size());
  std::vector<Vec3> expected_moment(p.size());
  std::size_t acting = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const std::uint32_t i = pairs.first[k];
    const std::uint32_t j = pairs.second[k];
    double* row = expected_history.data() + k * pairs.whole_stride();
    const AloneResult r = evaluate_alone(law, p, i, j, row, space);
    const ContactForce& f = r.force;
    if (f.on_first != Vec3{}) ++acting;
    // Bit for bit: the same operations on the same values (EXPECT_EQ on doubles is exact).
    EXPECT_EQ(out.force[k], f.on_first) << "pair " << k;
    if (f.on_first != Vec3{}) {
      EXPECT_EQ(out.point[k], r.point) << "pair " << k;
    }
    if constexpr (Law::has_couple) {
      EXPECT_EQ(out.couple[k], f.couple_on_first) << "pair " << k;
    }
    if constexpr (Space::periodic) {
      EXPECT_EQ(out.shift[k], r.shift) << "pair " << k;
    }
    std::vector<double> loop_row(pairs.whole_stride());
    pairs.copy_whole_row(k, loop_row.data());
    for (std::size_t c = 0; c < loop_row.size(); ++c) EXPECT_EQ(loop_row[c], row[c]) << "pair " << k << " column " << c;
    // The sums in contact order, as the loop adds them with one range (zero
    // terms of idle pairs change no bit of a non-zero sum).
    add_contact_load(expected_force[i], expected_moment[i], f.on_first, r.point - p.position[i]);
    expected_moment[i] += f.couple_on_first;
    add_contact_load(expected_force[j], expected_moment[j], -1.0 * f.on_first, r.arm_second);
    expected_moment[j] += -1.0 * f.couple_on_first;
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p.force[i], expected_force[i]) << "particle " << i;
    EXPECT_EQ(p.moment[i], expected_moment[i]) << "particle " << i;
  }
  // The chain must exercise more than one block and stage of acting pairs.
  EXPECT_GT(acting, pair_stage_size + 1);
  EXPECT_GT(pairs.size(), pair_block_size + 1);
  return pairs;
}

/// linear_pbond rows: two pairs in three bonded (intact), the others broken
/// earlier (no bond load); moments of the size of force x radius, so that the
/// peak stresses of the forces and of the moments are of one order.
void bonded_rows(std::size_t k, double* row) {
  for (std::size_t c = 4; c < 8; ++c) row[LinearPbondLaw::load_offset + c] *= radius;
  set_bond_state(row, k % 3 == 2 ? BondState::broken_tension : BondState::intact);
  if (k % 3 == 2) BondLoad::clear(row + LinearPbondLaw::load_offset);
}

/// Strengths within the spread of the random loads: in one step some bonds
/// stay intact and some break, in tension and in shear (asserted below).
LinearPbondLaw weak_bonds() {
  return {.emod = 1e8, .kratio = 2.0, .friction = 0.5, .damping_ratio_normal = 0.1, .bond_emod = 1e8, .bond_kratio = 2.0,
          .radius_multiplier = 1.0, .moment_factor = 1.0, .tensile_strength = 2e3, .cohesion = 1e3, .tan_friction_angle = 0.5,
          .damping_ratio_shear = 0.1};
}

TEST(PairLoop, LinearContactsAreWhatTheLawGivesEachContactAlone) {
  const LinearLaw law{.kn = 1e5, .ks = 2e4, .friction = 0.5, .damping_ratio_normal = 0.2, .damping_ratio_shear = 0.15};
  expect_loop_equals_law_alone(law, [](std::size_t, double*) {});
}

TEST(PairLoop, ParallelBondContactsAreWhatTheLawGivesEachContactAlone) {
  PairContacts after = expect_loop_equals_law_alone(weak_bonds(), bonded_rows);
  std::size_t intact = 0, broke_in_shear = 0, broke_in_tension_now = 0;
  for (std::size_t k = 0; k < after.size(); ++k) {
    const BondState s = bond_state(after.row(k));
    intact += s == BondState::intact;
    broke_in_shear += s == BondState::broken_shear;
    broke_in_tension_now += k % 3 != 2 && s == BondState::broken_tension;
  }
  EXPECT_GT(intact, 0U);
  EXPECT_GT(broke_in_shear, 0U);
  EXPECT_GT(broke_in_tension_now, 0U);
}

/// damage_bond rows, four kinds in turn: intact with the plastic parts, the
/// accumulated measures and the linear shear force +0 (a bond that never
/// yielded: the loop leaves +0 vectors unturned and unstored); damaged, with
/// random plastic parts; broken (every column cleared, as break_bond leaves
/// it); and never bonded (all +0). Displacements of about 1e-9 m and
/// rotations of 1e-6 rad, so that the loads are of the order of the
/// strengths of weak_damage_bonds.
void damage_bond_rows(std::size_t k, double* row) {
  using L = DamageBondLaw;
  double* plastic = row + L::hot_history_size;  // a whole row: the cold columns (plastic parts) last
  for (std::size_t c = L::opening; c < L::twist; ++c) row[c] *= 1e-6;
  for (std::size_t c = L::twist; c < L::accumulated_opening; ++c) row[c] *= 1e-3;
  for (std::size_t c = L::plastic_opening; c < L::plastic_bend; ++c) plastic[c] *= 1e-6;
  for (std::size_t c = L::plastic_bend; c < L::cold_history_size; ++c) plastic[c] *= 1e-3;
  for (std::size_t c = L::accumulated_opening; c < L::linear_shear; ++c) row[c] = std::abs(row[c]) * 1e-6;
  switch (k % 4) {
    case 0:
      for (std::size_t c = L::accumulated_opening; c < L::history_size; ++c) row[c] = 0.0;
      row[L::damage] = 0.0;
      set_bond_state(row, BondState::intact);
      break;
    case 1:
      row[L::damage] = 0.3;
      set_bond_state(row, BondState::damaged);
      break;
    case 2:
      for (std::size_t c = 1; c < L::linear_shear; ++c) row[c] = 0.0;
      for (std::size_t c = 0; c < L::cold_history_size; ++c) plastic[c] = 0.0;
      row[L::damage] = 1.0;
      set_bond_state(row, BondState::broken_shear);
      break;
    default:
      for (std::size_t c = 0; c < L::history_size; ++c) row[c] = 0.0;
  }
}

/// Strengths of the order of a step's loads (k̄ = 5e10 Pa/m times the
/// step's relative motion, 0.01 m/s x 1e-6 s, is 500 Pa) and softening
/// lengths of the plastic displacements: in one step some bonds stay
/// elastic, some yield, and some of those break (counted below: 25 / 115 / 74).
DamageBondLaw weak_damage_bonds() {
  return {.emod = 1e8, .kratio = 2.0, .friction = 0.5, .damping_ratio_normal = 0.1, .bond_emod = 1e8, .bond_kratio = 2.0,
          .radius_multiplier = 1.0, .tensile_strength = 300.0, .compressive_strength = 5e3, .cohesion = 1e3, .u_cn = 1e-9,
          .u_cs = 1e-9, .theta_c = 1e-5, .bond_gap = 1e-4, .damping_ratio_shear = 0.1};
}

TEST(PairLoop, DamageBondContactsAreWhatTheLawGivesEachContactAlone) {
  PairContacts after = expect_loop_equals_law_alone(weak_damage_bonds(), damage_bond_rows);
  std::size_t intact = 0, damaged_now = 0, broke_now = 0;
  for (std::size_t k = 0; k < after.size(); ++k) {
    const BondState s = bond_state(after.row(k));
    intact += s == BondState::intact;
    damaged_now += k % 4 == 0 && s == BondState::damaged;
    broke_now += k % 4 < 2 && !is_bonded(s);
  }
  EXPECT_GT(intact, 0U);
  EXPECT_GT(damaged_now, 0U);
  EXPECT_GT(broke_now, 0U);
}

TEST(PairLoop, ContactsThroughADeformingPeriodicBoundaryAreWhatTheLawGivesEachContactAlone) {
  // Periodic in y with a 10 mm edge; every odd sphere one edge up, so each
  // pair meets through the boundary image; the cell stretches at 2 /s along y.
  PeriodicCell cell;
  cell.lo = {-1.0, -5e-3, -1.0};
  cell.hi = {2.0, 5e-3, 1.0};
  cell.periodic = {false, true, false};
  cell.strain_rate = {0.0, 2.0, 0.0};
  const PeriodicSpace space(cell);
  expect_loop_equals_law_alone(weak_bonds(), bonded_rows, Vec3{0.0, 10e-3, 0.0}, space);
}

}  // namespace
}  // namespace dfc::dem
