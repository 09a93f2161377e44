// The DEM contact laws' keys, declared once (dem_contact_laws.hpp). Sources:
// Cundall & Strack (1979) and the Itasca PFC linear model (linear);
// Potyondy & Cundall (2004), doi 10.1016/j.ijrmms.2004.09.011 (linear_pbond);
// Itasca PFC softbond and Ma & Huang (2018) (soft_bond); Zheng & Ciantia
// (2025), doi 10.1007/s00603-025-04411-0 (damage_bond). Equations:
// docs/theory/dem_contact_laws.md.
#include "dfc/common/sections/dem_contact_laws.hpp"

namespace dfc::sections {

namespace {

using P = ParameterDeclaration;

constexpr Bounds kNonNegative{0.0};
constexpr Bounds kFraction{0.0, 1.0};
constexpr Bounds kAngle{0.0, 90.0};

// Upscaling by S: lengths and stiffnesses given in N/m scale with S (exponent
// 1); moduli, ratios and strengths stay fixed (exponent 0), the
// deformability method makes the stiffnesses follow the radii.
P scales_with_s(P p) { return p.upscaled("scales with S", 1.0); }

P friction(const char* of) {
  return P::number("friction", "-", std::string("Coulomb friction coefficient mu") + of).within(kNonNegative).fallback(0.5);
}
P damping_normal(const char* of) {
  return P::number("damping_ratio_normal", "-", std::string("normal viscous damping") + of + ", fraction of critical").within(kFraction).fallback(0.0);
}
P damping_shear(const char* of) {
  return P::number("damping_ratio_shear", "-", std::string("shear viscous damping") + of + ", fraction of critical, cut while it slides")
      .within(kFraction)
      .fallback(0.0);
}
P bond_gap() {
  return scales_with_s(P::number("bond_gap_m", "m", "pairs whose surface gap is at most this at start are bonded").within(kNonNegative).fallback(0.0));
}
P linear_modulus(const char* of) {
  return P::number("emod_pa", "Pa", std::string("effective modulus E*") + of + ", k_n = pi E* R_min^2/(R1+R2)").positive();
}
P stiffness_ratio(const char* key, const char* doc) { return P::number(key, "-", doc).positive().fallback(1.0); }

}  // namespace

const SectionDeclaration& linear_law() {
  static const SectionDeclaration s{
      .name = "dem.contact.linear",
      .doc = "PFC linear model: no-tension normal spring, incremental shear spring with Coulomb slip, optional dashpots",
      .parameters = {scales_with_s(P::number("kn_n_m", "N/m", "normal contact stiffness k_n").positive()),
                     scales_with_s(P::number("ks_n_m", "N/m", "shear contact stiffness k_s").within(kNonNegative)),
                     friction(": |F_s| <= mu F_n"),
                     P::number("damping_ratio_normal", "-", "normal viscous damping as a fraction beta_n of critical, c_n = 2 beta_n sqrt(m_eff k_n)")
                         .within(kFraction)
                         .fallback(0.0),
                     P::number("damping_ratio_shear", "-",
                               "shear viscous damping as a fraction beta_s of critical, c_s = 2 beta_s sqrt(m_eff k_s), cut while the contact slides")
                         .within(kFraction)
                         .fallback(0.0)},
  };
  return s;
}

const SectionDeclaration& linear_pbond_law() {
  static const SectionDeclaration s{
      .name = "dem.contact.linear_pbond",
      .doc = "linear parallel bond: linear frictional contact plus a brittle elastic bond disc carrying force and moment",
      .parameters = {linear_modulus(" of the linear part"),
                     stiffness_ratio("kratio", "normal-to-shear stiffness ratio kappa* of the linear part"),
                     friction(" of the linear part"),
                     damping_normal(" of the linear part"),
                     P::number("pb_emod_pa", "Pa", "bond effective modulus Ebar*, kbar_n = Ebar*/(R1+R2) [Pa/m]").positive(),
                     stiffness_ratio("pb_kratio", "bond normal-to-shear stiffness ratio kappabar*"),
                     stiffness_ratio("pb_rmul", "bond radius multiplier lambdabar: Rbar = lambdabar min(R1, R2)"),
                     P::number("pb_mcf", "-", "moment-contribution factor betabar of the peak stresses").within(kFraction).fallback(1.0),
                     P::number("pb_ten_pa", "Pa", "bond tensile strength sigmabar_c").positive(),
                     P::number("pb_coh_pa", "Pa", "bond cohesion cbar").positive(),
                     P::number("pb_fa_deg", "deg", "bond friction angle phibar: tau_c = cbar - sigma tan(phibar)").within(kAngle).fallback(0.0),
                     bond_gap(),
                     damping_shear(" of the linear part")},
  };
  return s;
}

const SectionDeclaration& soft_bond_law() {
  static const SectionDeclaration s{
      .name = "dem.contact.soft_bond",
      .doc = "soft bond: linear softening in tension, brittle in shear, then linear frictional",
      .parameters = {P::number("sb_emod_pa", "Pa", "effective modulus E* of the bond disc, k_n = E*/(R1+R2) [Pa/m] bonded and unbonded").positive(),
                     stiffness_ratio("kratio", "normal-to-shear stiffness ratio kappa*"),
                     friction(" of the unbonded contact"),
                     damping_normal(" of the unbonded contact"),
                     stiffness_ratio("sb_rmul", "radius multiplier lambda: Rbar = lambda min(R1, R2)"),
                     P::number("sb_mcf", "-", "moment-contribution factor beta of the peak stresses").within(kFraction).fallback(1.0),
                     P::number("sb_ten_pa", "Pa", "tensile strength sigma_t (start of softening)").positive(),
                     P::number("sb_coh_pa", "Pa", "cohesion c of the brittle shear strength").positive(),
                     P::number("sb_fa_deg", "deg", "friction angle phi: tau_c = c - sigma tan(phi)").within(kAngle).fallback(0.0),
                     P::number("sb_soft", "-", "softening factor zeta: softening slope -k_n/zeta (0: brittle in tension)").within(kNonNegative).fallback(0.0),
                     P::number("sb_cut", "-", "softening tensile strength factor gamma: broken when the softened strength is gamma sigma_t")
                         .within(kFraction)
                         .fallback(0.0),
                     bond_gap(),
                     damping_shear(" of the unbonded contact")},
  };
  return s;
}

const SectionDeclaration& damage_bond_law() {
  static const SectionDeclaration s{
      .name = "dem.contact.damage_bond",
      .doc = "Zheng-Ciantia damage-plasticity bond: N-V-M envelope, associated flow, damage D shrinking stiffness and capacities",
      .parameters = {linear_modulus(" of the linear contact"),
                     stiffness_ratio("kratio", "normal-to-shear stiffness ratio kappa* of the linear contact"),
                     friction(" of the linear contact"),
                     damping_normal(" of the linear contact"),
                     P::number("bond_emod_pa", "Pa", "bond effective modulus Ebar*, kbar_n = Ebar*/(R1+R2) [Pa/m]").positive(),
                     stiffness_ratio("bond_kratio", "bond normal-to-shear stiffness ratio kappabar*"),
                     stiffness_ratio("bond_rmul", "bond radius multiplier lambda: Rbar = lambda min(R1, R2)"),
                     P::number("ten_pa", "Pa", "bond tensile strength sigma_t (Nbar in tension, Mtilde)").positive(),
                     P::number("com_pa", "Pa", "bond compressive strength sigma_c (Nbar in compression)").positive(),
                     P::number("coh_pa", "Pa", "bond shear strength C (Vbar)").positive(),
                     scales_with_s(P::number("ucn_m", "m", "normal softening length u_cn of the damage law").positive()),
                     scales_with_s(P::number("ucs_m", "m", "shear softening length u_cs of the damage law").positive()),
                     P::number("theta_c_rad", "rad", "bending softening rotation theta_c of the damage law").positive(),
                     bond_gap(),
                     damping_shear(" of the linear contact")},
  };
  return s;
}

const SectionDeclaration& dem_contact() {
  static const SectionDeclaration s{
      .name = "dem.contact",
      .doc = "the contact law and its parameters (dem_server --help lists each law's stiffness formulas and sources)",
      .parameters = {P::string("law", "contact law").one_of({"linear", "linear_pbond", "soft_bond", "damage_bond"}).fallback("linear")},
      .selector = "law",
      .variants = {{"linear", linear_law().doc, &linear_law()},
                   {"linear_pbond", linear_pbond_law().doc, &linear_pbond_law()},
                   {"soft_bond", soft_bond_law().doc, &soft_bond_law()},
                   {"damage_bond", damage_bond_law().doc, &damage_bond_law()}},
  };
  return s;
}

}  // namespace dfc::sections
