// The shear dashpot of the frictional contact that every bonded law keeps
// beside (linear_pbond) or after (soft_bond, damage_bond) its bond: the
// scenario key `damping_ratio_shear` reaches the `linear` law inside each
// (linear_law.hpp), which adds c_s v_t, c_s = 2 beta_s sqrt(m_eff k_s)
// (docs/theory/dem_contact_laws.md §2.3), while the contact sticks.
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "dfc/dem/contact_law_registry.hpp"

namespace dfc::dem {
namespace {

constexpr double radius = 1e-3;        // both spheres
constexpr double emod = 1e8;           // Pa, E* of the frictional contact
constexpr double kratio = 2.5;         // k_n / k_s
constexpr double tangential = 1e-3;    // m/s, v_t along x
constexpr double beta = 0.2;

ContactKinematics sticking_contact() {
  ContactKinematics k;
  k.normal = {0.0, 0.0, 1.0};
  k.overlap = 1e-6;  // mu F_n stays far above the shear force of one step
  k.relative_velocity = {tangential, 0.0, 0.0};
  k.effective_mass = 1e-5;
  k.radius_first = k.radius_second = radius;
  k.dt = 1e-6;
  return k;
}

/// The x force on the first body of a contact whose bond is broken, without
/// and with the shear dashpot.
template <class Law>
std::pair<double, double> broken_bond_shear_force(nlohmann::json parameters) {
  std::pair<double, double> forces;
  for (const double damping : {0.0, beta}) {
    parameters["damping_ratio_shear"] = damping;
    const Law law = std::get<Law>(make_contact_law(parameters).law);
    std::vector<double> history(Law::history_size, 0.0);
    set_bond_state(history.data(), BondState::broken_shear);
    (damping == 0.0 ? forces.first : forces.second) = law.evaluate(sticking_contact(), history.data()).on_first.x;
  }
  return forces;
}

/// Spring k_s v_t dt without the dashpot; the dashpot adds c_s v_t. The
/// spring is one product (1e-15); the difference of two sums each rounded
/// once at the size of the larger term (the dashpot's, 1e3 times the spring's
/// here), so 1e-12 of it.
void expect_spring_then_dashpot(std::pair<double, double> forces, double ks) {
  const ContactKinematics k = sticking_contact();
  const double spring = ks * tangential * k.dt;
  const double dashpot = 2.0 * beta * std::sqrt(k.effective_mass * ks) * tangential;
  EXPECT_NEAR(forces.first, spring, 1e-15 * spring);
  EXPECT_NEAR(forces.second - forces.first, dashpot, 1e-12 * dashpot);
}

TEST(BondedShearDashpot, LinearPbondsFrictionalPart) {
  const auto forces = broken_bond_shear_force<LinearPbondLaw>(
      {{"law", "linear_pbond"}, {"emod_pa", emod}, {"kratio", kratio}, {"pb_emod_pa", emod}, {"pb_ten_pa", 1e6}, {"pb_coh_pa", 1e6}});
  // Reference §2.2: k_n = pi E* R_min^2 / (R1 + R2) = pi E* R / 2 for equal spheres.
  expect_spring_then_dashpot(forces, std::numbers::pi * emod * radius / 2.0 / kratio);
}

TEST(BondedShearDashpot, SoftBondsUnbondedContact) {
  const auto forces = broken_bond_shear_force<SoftBondLaw>(
      {{"law", "soft_bond"}, {"sb_emod_pa", emod}, {"kratio", kratio}, {"sb_ten_pa", 1e6}, {"sb_coh_pa", 1e6}});
  // docs/dem_bond_laws.md: the unbonded contact keeps the bond's stiffness
  // E*/(R1 + R2) [Pa/m] times the section pi (lambda R)^2, lambda = 1.
  expect_spring_then_dashpot(forces, emod / (2.0 * radius) * std::numbers::pi * radius * radius / kratio);
}

TEST(BondedShearDashpot, DamageBondsLinearContact) {
  const auto forces = broken_bond_shear_force<DamageBondLaw>({{"law", "damage_bond"},
                                                              {"emod_pa", emod},
                                                              {"kratio", kratio},
                                                              {"bond_emod_pa", emod},
                                                              {"ten_pa", 1e6},
                                                              {"com_pa", 1e7},
                                                              {"coh_pa", 1e6},
                                                              {"ucn_m", 1e-6},
                                                              {"ucs_m", 1e-6},
                                                              {"theta_c_rad", 1e-3}});
  expect_spring_then_dashpot(forces, std::numbers::pi * emod * radius / 2.0 / kratio);
}

}  // namespace
}  // namespace dfc::dem
