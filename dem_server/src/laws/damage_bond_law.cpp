#include "dfc/dem/damage_bond_law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dfc::dem {

std::vector<HistoryColumn> DamageBondLaw::history_columns() {
  return {{"bond_state", "-"},        {"damage", "-"},           {"opening", "m"},          {"slip_x", "m"},
          {"slip_y", "m"},            {"slip_z", "m"},           {"twist", "rad"},          {"bend_x", "rad"},
          {"bend_y", "rad"},          {"bend_z", "rad"},         {"plastic_opening", "m"},  {"plastic_slip_x", "m"},
          {"plastic_slip_y", "m"},    {"plastic_slip_z", "m"},   {"plastic_bend_x", "rad"}, {"plastic_bend_y", "rad"},
          {"plastic_bend_z", "rad"},  {"accumulated_plastic_opening", "m"}, {"accumulated_plastic_slip", "m"},
          {"accumulated_plastic_bend", "rad"}, {"shear_force_x", "N"}, {"shear_force_y", "N"}, {"shear_force_z", "N"}};
}

DamageBondLaw DamageBondLaw::from_parameters(const LawParameters& p) {
  return {.emod = p["emod_pa"], .kratio = p["kratio"], .friction = p["friction"], .damping_ratio_normal = p["damping_ratio_normal"],
          .bond_emod = p["bond_emod_pa"], .bond_kratio = p["bond_kratio"], .radius_multiplier = p["bond_rmul"], .tensile_strength = p["ten_pa"],
          .compressive_strength = p["com_pa"], .cohesion = p["coh_pa"], .u_cn = p["ucn_m"], .u_cs = p["ucs_m"], .theta_c = p["theta_c_rad"],
          .bond_gap = p["bond_gap_m"], .damping_ratio_shear = p["damping_ratio_shear"]};
}

double DamageBondLaw::damage_from(double opening_p, double slip_p, double bend_p) const noexcept {
  return 1.0 - std::exp(-(opening_p / u_cn + slip_p / u_cs + bend_p / theta_c));
}

namespace {

/// Unit vector of v, or zero.
Vec3 direction(const Vec3& v) noexcept {
  const double l = norm(v);
  return l > 0.0 ? (1.0 / l) * v : Vec3{};
}

}  // namespace

ContactForce DamageBondLaw::update_bond(const ContactKinematics& k, double* h) const noexcept {
  const Vec3& n = k.normal;
  const BondSection s = bond_section(k, radius_multiplier);
  const double kn = deformability_bond_kn(k, bond_emod);
  const double ks = kn / bond_kratio;

  // 1. Total displacements (rotated with the contact plane) and the plastic parts.
  const BondIncrements d = bond_increments(k);
  const ContactTwirl twirl = ContactTwirl::of(k);
  const double u_n = h[opening] + d.normal;
  const Vec3 u_s = load_in_plane(h + slip, k.normal, twirl) + d.shear;
  const double theta_t = h[twist] + d.twist;
  const Vec3 theta_b = load_in_plane(h + bend, k.normal, twirl) + d.bend;
  double u_np = h[plastic_opening];
  Vec3 u_sp = load_in_plane(h + plastic_slip, k.normal, twirl);
  Vec3 theta_bp = load_in_plane(h + plastic_bend, k.normal, twirl);

  // 2. Elastic trial in normalised coordinates (the (1-D) factors cancel).
  double e_n = u_n - u_np;
  Vec3 e_s = u_s - u_sp;
  Vec3 e_b = theta_b - theta_bp;
  const double sigma_0 = e_n >= 0.0 ? tensile_strength : compressive_strength;
  const EnvelopePoint trial{kn * e_n / sigma_0, ks * norm(e_s) / cohesion, kn * norm(e_b) * s.radius / tensile_strength};
  double damage_value = h[damage];
  if (outside_damage_envelope(trial)) {
    // 3. Closest-point return (energy norm) and the plastic increments it implies.
    const ReturnWeights w{sigma_0 * sigma_0 / kn, cohesion * cohesion / ks, tensile_strength * tensile_strength / (4.0 * kn)};
    const EnvelopePoint x = closest_admissible_point(trial, w);
    const double e_n_new = x.n * sigma_0 / kn;
    const Vec3 e_s_new = (x.v * cohesion / ks) * direction(e_s);
    const Vec3 e_b_new = (x.m * tensile_strength / (kn * s.radius)) * direction(e_b);
    h[accumulated_opening] += std::abs(e_n - e_n_new);
    h[accumulated_slip] += norm(e_s - e_s_new);
    h[accumulated_bend] += norm(e_b - e_b_new);
    u_np += e_n - e_n_new;
    u_sp += e_s - e_s_new;
    theta_bp += e_b - e_b_new;
    e_n = e_n_new;
    e_s = e_s_new;
    e_b = e_b_new;
    // 4. Damage (corrected Eq. 2), never lowered.
    damage_value = std::max(damage_value, damage_from(h[accumulated_opening], h[accumulated_slip], h[accumulated_bend]));
  }

  // 5. Breakage (§3.6): the bond and its displacements are removed.
  if (damage_value > breakage_damage) {
    const double normal_term = h[accumulated_opening] / u_cn;
    const bool tensile = e_n >= 0.0 && normal_term >= h[accumulated_slip] / u_cs && normal_term >= h[accumulated_bend] / theta_c;
    for (std::size_t c = 1; c < linear_shear; ++c) h[c] = 0.0;
    h[damage] = 1.0;
    set_bond_state(h, tensile ? BondState::broken_tension : BondState::broken_shear);
    return {};
  }
  h[damage] = damage_value;
  set_bond_state(h, damage_value > 0.0 ? BondState::damaged : BondState::intact);
  h[opening] = u_n;
  store_vec3(h + slip, u_s);
  h[twist] = theta_t;
  store_vec3(h + bend, theta_b);
  h[plastic_opening] = u_np;
  store_vec3(h + plastic_slip, u_sp);
  store_vec3(h + plastic_bend, theta_bp);

  // 6. Forces (Eq. 1) on the first body: tension pulls it along +n.
  const double intact = 1.0 - damage_value;
  const double normal_force = intact * kn * s.area * e_n;
  const Vec3 shear_force = (intact * ks * s.area) * e_s;
  const Vec3 couple = (intact * kn * s.inertia) * e_b + (intact * ks * s.polar * theta_t) * n;
  return {shear_force + normal_force * n, couple};
}

}  // namespace dfc::dem
