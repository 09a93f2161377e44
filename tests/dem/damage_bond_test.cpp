// Properties of the damage_bond law on a combined cyclic N–V–M path
// (docs/theory/dem_contact_laws.md §3): after every step the elastic state lies
// inside the envelope (f <= 0), D never decreases, and D equals the
// corrected Eq. 2 of its accumulated plastic measures.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "dfc/common/sections/dem_contact_laws.hpp"
#include "dfc/dem/contact_law_registry.hpp"

namespace dfc::dem {
namespace {

DamageBondLaw seed001_law() {  // Ciantia et al. 2024 Table 1 (no shear dashpot: the last value)
  const std::vector<double> values{1.7e9, 5.0, 0.5, 0.0, 1.7e9, 5.0, 1.0, 1e6, 50e6, 2e6, 2e-5, 2e-5, 6e-3, 0.0, 0.0};  // declaration order
  return DamageBondLaw::from_parameters(LawParameters(sections::damage_bond_law().parameters, values));
}

TEST(DamageBond, CombinedCyclicPathStaysInsideTheEnvelopeWithMonotoneDamage) {
  const DamageBondLaw law = seed001_law();
  std::vector<double> h(DamageBondLaw::history_size, 0.0);
  set_bond_state(h.data(), BondState::intact);
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = -1e-9;
  k.radius_first = k.radius_second = 1e-3;
  k.effective_mass = 1e-6;
  k.dt = 1e-6;
  const double r = 1e-3, kn = 1.7e9 / (2 * r), ks = kn / 5.0;
  double previous_damage = 0.0;
  int yielded = 0;
  for (int step = 0; step < 3000 && is_bonded(bond_state(h.data())); ++step) {
    // A rotating mix of opening/closing, shear in x and y, bending and twist.
    const double phase = 0.01 * step;
    k.relative_velocity = {0.02 * std::cos(phase), 0.01 * std::sin(2 * phase), 0.015 * std::sin(phase)};
    k.relative_angular_velocity = {5.0 * std::cos(1.3 * phase), 3.0 * std::sin(0.7 * phase), 4.0};
    const double before = h[DamageBondLaw::damage];
    (void)law.evaluate(k, h.data());
    if (!is_bonded(bond_state(h.data()))) break;
    const double D = h[DamageBondLaw::damage];
    if (D > before) ++yielded;
    EXPECT_GE(D, previous_damage) << "step " << step;
    previous_damage = D;
    // D reproduces Eq. 2 (corrected, §3.4) from the stored accumulated measures: same formula, 1 ulp-level.
    EXPECT_NEAR(D, 1.0 - std::exp(-(h[DamageBondLaw::accumulated_opening] / 2e-5 + h[DamageBondLaw::accumulated_slip] / 2e-5 +
                                    h[DamageBondLaw::accumulated_bend] / 6e-3)), 1e-14);
    // f <= 0 at the stored elastic displacements (normalised as in damage_bond_law.hpp).
    const double* plastic = h.data() + DamageBondLaw::hot_history_size;  // a whole row: the cold columns last
    const double en = h[DamageBondLaw::opening] - plastic[DamageBondLaw::plastic_opening];
    const Vec3 es = load_vec3(h.data() + DamageBondLaw::slip) - load_vec3(plastic + DamageBondLaw::plastic_slip);
    const Vec3 eb = load_vec3(h.data() + DamageBondLaw::bend) - load_vec3(plastic + DamageBondLaw::plastic_bend);
    const EnvelopePoint x{kn * en / (en >= 0 ? 1e6 : 50e6), ks * norm(es) / 2e6, kn * norm(eb) * r / 1e6};
    // The return stops at f in [-1e-9, 0]; re-forming the normalised point
    // from stored displacements adds rounding of ~1e-15.
    EXPECT_LE(damage_envelope(x), 1e-13) << "step " << step;
  }
  EXPECT_GT(yielded, 10);  // the path must actually exercise the return
}

TEST(DamageBond, LinearContactActsOnlyOnceDamaged) {
  const DamageBondLaw law = seed001_law();
  std::vector<double> h(DamageBondLaw::history_size, 0.0);
  set_bond_state(h.data(), BondState::intact);
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = 1e-7;  // overlapping, but the intact bond alone acts (dem_contact_laws.md §3.6)
  k.radius_first = k.radius_second = 1e-3;
  k.dt = 1e-6;
  const ContactForce f = law.evaluate(k, h.data());
  EXPECT_EQ(f.on_first.z, 0.0);  // no motion: the bond carries nothing, and no linear force
  set_bond_state(h.data(), BondState::broken_shear);
  const ContactForce g = law.evaluate(k, h.data());
  // Broken: the linear contact k_n = π E* R²/(2R) times the overlap, pushing the first body away.
  EXPECT_NEAR(g.on_first.z, -M_PI * 1.7e9 * 1e-3 / 2.0 * 1e-7, 1e-12);
}

// The fast path of update_bond: where surely_elastic holds, the full test
// of the elastic trial (outside_damage_envelope, with the divisions and
// square roots it needs) must find the trial inside, or the fast path would
// skip a return. Sampled around the fast path's bounds (1/2, 1/2, 1/4 of the
// capacities) and up to 1.5 times the capacities, in tension and compression.
TEST(DamageBond, SurelyElasticTrialsAreInsideTheEnvelope) {
  const DamageBondLaw law = seed001_law();
  ContactKinematics k;
  k.radius_first = 1e-3;
  k.radius_second = 0.6e-3;
  double c[DamageBondLaw::constants_size];
  law.pair_constants(k, c);
  const double kn = c[DamageBondLaw::bond_kn], ks = c[DamageBondLaw::bond_ks], r = law.radius_multiplier * 0.6e-3;
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<double> u(-1.0, 1.0), share(0.0, 1.0);
  int fast = 0, slow = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    // Target ratios n, v, m of the trial point, then the strains that give them.
    const double n = 1.5 * u(rng), v = 0.75 * share(rng), m = 0.4 * share(rng);
    const double sigma_0 = n >= 0.0 ? law.tensile_strength : law.compressive_strength;
    const Vec3 slip_direction = Vec3{u(rng), u(rng), 0.0};
    const Vec3 bend_direction = Vec3{u(rng), u(rng), 0.0};
    DamageBondLaw::Strain e;
    e.opening = n * sigma_0 / kn;
    e.slip = (v * law.cohesion / ks / norm(slip_direction)) * slip_direction;
    e.bend = (m * law.tensile_strength / (kn * r) / norm(bend_direction)) * bend_direction;
    if (!law.surely_elastic(e, c, k)) {
      ++slow;
      continue;
    }
    ++fast;
    const EnvelopePoint point{kn * e.opening / sigma_0, ks * norm(e.slip) / law.cohesion, kn * norm(e.bend) * r / law.tensile_strength};
    ASSERT_FALSE(outside_damage_envelope(point)) << "n " << point.n << " v " << point.v << " m " << point.m;
  }
  // Both paths were sampled.
  EXPECT_GT(fast, 10000);
  EXPECT_GT(slow, 10000);
}

// The split row (contact_model.hpp SplitsHistory): a bond that has not
// yielded neither reads nor writes its plastic parts, so the pair loop need
// not bring them from memory. The cold row holds NaN here: read, it would
// make the force NaN; written, its bits would change. Once the bond yields,
// the plastic parts are written and the accumulated measures that announce
// them are positive.
TEST(DamageBond, ABondThatHasNotYieldedLeavesItsPlasticRowUntouched) {
  const DamageBondLaw law = seed001_law();
  std::vector<double> hot(DamageBondLaw::hot_history_size, 0.0);
  std::vector<double> cold(DamageBondLaw::cold_history_size, std::numeric_limits<double>::quiet_NaN());
  const std::vector<double> untouched = cold;
  set_bond_state(hot.data(), BondState::intact);
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = -1e-9;
  k.radius_first = k.radius_second = 1e-3;
  k.effective_mass = 1e-6;
  k.dt = 1e-6;
  double c[DamageBondLaw::constants_size];
  law.pair_constants(k, c);
  const auto step = [&](const Vec3& velocity) {
    k.relative_velocity = velocity;
    rotate_in_plane_history<DamageBondLaw>(hot.data(), k);
    return law.evaluate_in_plane(k, c, hot.data(), cold.data());
  };
  // 100 steps of 1e-9 m opening and shear: 1e-7 m, a tenth of the opening at
  // the tensile strength (sigma_t / k_n = 1e6 / 8.5e11 = 1.2e-6 m).
  for (int s = 0; s < 100; ++s) {
    const ContactForce f = step({1e-3, 0.0, 1e-3});
    ASSERT_TRUE(std::isfinite(f.on_first.x) && std::isfinite(f.on_first.z)) << "step " << s;
  }
  EXPECT_EQ(bond_state(hot.data()), BondState::intact);
  EXPECT_GT(hot[DamageBondLaw::opening], 0.9e-7);
  for (std::size_t i = 0; i < cold.size(); ++i) EXPECT_EQ(std::bit_cast<std::uint64_t>(cold[i]), std::bit_cast<std::uint64_t>(untouched[i]));
  // Pulled apart at 0.1 m/s (1e-7 m a step) from zeros: it yields within 20 steps.
  std::fill(cold.begin(), cold.end(), 0.0);
  for (int s = 0; s < 20 && !DamageBondLaw::plastic_in_use(hot.data()); ++s) (void)step({0.0, 0.0, 0.1});
  ASSERT_TRUE(DamageBondLaw::plastic_in_use(hot.data()));
  EXPECT_EQ(bond_state(hot.data()), BondState::damaged);
  EXPECT_GT(cold[DamageBondLaw::plastic_opening], 0.0);
  EXPECT_GT(hot[DamageBondLaw::accumulated_opening], 0.0);
}

}  // namespace
}  // namespace dfc::dem
