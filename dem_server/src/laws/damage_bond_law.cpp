#include "dfc/dem/damage_bond_law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dfc::dem {

std::vector<HistoryColumn> DamageBondLaw::history_columns() {
  return {{"bond_state", "-"},        {"damage", "-"},           {"opening", "m"},          {"slip_x", "m"},
          {"slip_y", "m"},            {"slip_z", "m"},           {"twist", "rad"},          {"bend_x", "rad"},
          {"bend_y", "rad"},          {"bend_z", "rad"},         {"accumulated_plastic_opening", "m"}, {"accumulated_plastic_slip", "m"},
          {"accumulated_plastic_bend", "rad"}, {"shear_force_x", "N"}, {"shear_force_y", "N"}, {"shear_force_z", "N"},
          {"plastic_opening", "m"},   {"plastic_slip_x", "m"},   {"plastic_slip_y", "m"},   {"plastic_slip_z", "m"},
          {"plastic_bend_x", "rad"},  {"plastic_bend_y", "rad"}, {"plastic_bend_z", "rad"}};
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

double DamageBondLaw::yield(Strain& e, const double* c, const ContactKinematics& k, double* h) const noexcept {
  const double kn = c[bond_kn], ks = c[bond_ks], radius = bond_section(k, radius_multiplier).radius;
  const double sigma_0 = e.opening >= 0.0 ? tensile_strength : compressive_strength;
  const EnvelopePoint trial{kn * e.opening / sigma_0, ks * norm(e.slip) / cohesion, kn * norm(e.bend) * radius / tensile_strength};
  double damage_value = h[damage];
  if (!outside_damage_envelope(trial)) return damage_value;
  // Closest-point return (energy norm) and the plastic increments it implies.
  const ReturnWeights w{sigma_0 * sigma_0 / kn, cohesion * cohesion / ks, tensile_strength * tensile_strength / (4.0 * kn)};
  const EnvelopePoint x = closest_admissible_point(trial, w);
  const double opening_new = x.n * sigma_0 / kn;
  const Vec3 slip_new = (x.v * cohesion / ks) * direction(e.slip);
  const Vec3 bend_new = (x.m * tensile_strength / (kn * radius)) * direction(e.bend);
  h[accumulated_opening] += std::abs(e.opening - opening_new);
  h[accumulated_slip] += norm(e.slip - slip_new);
  h[accumulated_bend] += norm(e.bend - bend_new);
  e.plastic_opening += e.opening - opening_new;
  e.plastic_slip += e.slip - slip_new;
  e.plastic_bend += e.bend - bend_new;
  e.opening = opening_new;
  e.slip = slip_new;
  e.bend = bend_new;
  // Damage (corrected Eq. 2), never lowered.
  return std::max(damage_value, damage_from(h[accumulated_opening], h[accumulated_slip], h[accumulated_bend]));
}

void DamageBondLaw::break_bond(double elastic_opening, double* h, double* p) const noexcept {
  const double normal_term = h[accumulated_opening] / u_cn;
  const bool tensile = elastic_opening >= 0.0 && normal_term >= h[accumulated_slip] / u_cs && normal_term >= h[accumulated_bend] / theta_c;
  if (plastic_in_use(h)) std::fill_n(p, cold_history_size, 0.0);
  for (std::size_t c = 1; c < linear_shear; ++c) h[c] = 0.0;
  h[damage] = 1.0;
  set_bond_state(h, tensile ? BondState::broken_tension : BondState::broken_shear);
}

}  // namespace dfc::dem
