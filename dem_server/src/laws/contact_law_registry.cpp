#include "dfc/dem/contact_law_registry.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "dfc/common/errors.hpp"
#include "dfc/common/sections/dem_contact_laws.hpp"

namespace dfc::dem {

namespace {

template <class Law>
ContactLaw make_law(const LawParameters& values) {
  return ContactLaw{Law::from_parameters(values)};
}

// What emod_pa sets wherever a law reads it: the linear frictional contact,
// a bar of section pi R_min^2 and length R1 + R2 (the PFC deformability method).
const std::string linear_contact_formula = "k_n = pi E* R_min^2/(R1+R2) [N/m], k_s = k_n/kratio";
const std::string deformability_source = "Potyondy & Cundall (2004); Itasca PFC linear model (deformability); docs/theory/dem_contact_laws.md §2.2";

std::vector<ContactLawInfo> build_registry() {
  std::vector<ContactLawInfo> table;
  table.push_back({
      .keyword = std::string(LinearLaw::keyword),
      .summary = "PFC linear model: no-tension normal spring, incremental shear spring with Coulomb slip, optional normal dashpot",
      .reference = "Itasca PFC linear model; Cundall & Strack (1979); docs/theory/dem_contact_laws.md §2.3",
      .upscaling_rule = "k_n and k_s scale with S (stiffness ~ E* R, Thakur et al. 2015); friction and damping ratio stay fixed",
      .parameters = sections::linear_law().parameters,
      .history = LinearLaw::history_columns(),
      .make = &make_law<LinearLaw>,
      .stiffness = {{"kn_n_m", "k_n = kn_n_m [N/m], the same for every pair", "Cundall & Strack (1979); docs/theory/dem_contact_laws.md §2.3"},
                    {"ks_n_m", "k_s = ks_n_m [N/m], the same for every pair", "Cundall & Strack (1979); docs/theory/dem_contact_laws.md §2.3"}},
      .renamed = {},
  });
  table.push_back({
      .keyword = std::string(LinearPbondLaw::keyword),
      .summary = "linear parallel bond: linear frictional contact plus a brittle elastic bond disc carrying force and moment",
      .reference = "Potyondy & Cundall (2004) IJRMMS 41:1329; Itasca PFC linearpbond; docs/theory/dem_contact_laws.md §2",
      .upscaling_rule = "E*, Ebar*, stiffness ratios, lambda, beta and strengths stay fixed (stiffnesses follow R); bond_gap_m scales with S",
      .parameters = sections::linear_pbond_law().parameters,
      .history = LinearPbondLaw::history_columns(),
      .make = &make_law<LinearPbondLaw>,
      .stiffness = {{"emod_pa", linear_contact_formula, deformability_source},
                    {"pb_emod_pa", "kbar_n = Ebar*/(R1+R2) [Pa/m] on the disc A = pi (pb_rmul R_min)^2, kbar_s = kbar_n/pb_kratio",
                     "Potyondy & Cundall (2004) parallel bond; docs/theory/dem_contact_laws.md §2.1-2.3"}},
      .renamed = {},
  });
  table.push_back({
      .keyword = std::string(SoftBondLaw::keyword),
      .summary = "soft bond: linear softening in tension (inferred form, docs/dem_bond_laws.md), brittle in shear, then linear frictional",
      .reference = "Itasca PFC softbond; Ma & Huang (2018); docs/theory/dem_contact_laws.md §1 (equations inferred, §1.2)",
      .upscaling_rule = "E*, kappa*, lambda, beta, strengths, zeta and gamma stay fixed (stiffness follows R); bond_gap_m scales with S",
      .parameters = sections::soft_bond_law().parameters,
      .history = SoftBondLaw::history_columns(),
      .make = &make_law<SoftBondLaw>,
      .stiffness = {{"sb_emod_pa",
                     "k_n = E*/(R1+R2) [Pa/m] on the disc A = pi (sb_rmul R_min)^2, k_s = k_n/kratio, bonded and unbonded (k_n A [N/m] after breakage)",
                     "Itasca PFC softbond (one stiffness set, bonded and unbonded); docs/theory/dem_contact_laws.md §1.1-1.2"}},
      .renamed = {{"emod_pa", "sb_emod_pa",
                   "soft_bond's modulus sets its bond disc, k_n = E*/(R1+R2) [Pa/m] on pi (sb_rmul R_min)^2, also after breakage; "
                   "emod_pa is the linear contact's modulus (k_n = pi E* R_min^2/(R1+R2) [N/m] in linear_pbond and damage_bond), "
                   "which differs by sb_rmul^2"}},
  });
  table.push_back({
      .keyword = std::string(DamageBondLaw::keyword),
      .summary = "Zheng-Ciantia damage-plasticity bond: N-V-M envelope, associated flow, damage D shrinking stiffness and capacities",
      .reference = "Zheng & Ciantia (2025) RMRE doi 10.1007/s00603-025-04411-0; docs/theory/dem_contact_laws.md §3; Ciantia et al. 2024 Eqs. 1-2",
      .upscaling_rule = "moduli, stiffness ratios, strengths and theta_c stay fixed; ucn_m, ucs_m and bond_gap_m scale with S (guide Eq. 5)",
      .parameters = sections::damage_bond_law().parameters,
      .history = DamageBondLaw::history_columns(),
      .make = &make_law<DamageBondLaw>,
      .stiffness = {{"emod_pa", linear_contact_formula + ", once the bond is damaged or broken",
                     deformability_source + "; Zheng & Ciantia (2025) §3.6"},
                    {"bond_emod_pa",
                     "kbar_n = Ebar*/(R1+R2) [Pa/m] on the disc A = pi (bond_rmul R_min)^2, kbar_s = kbar_n/bond_kratio, times (1 - D)",
                     "Zheng & Ciantia (2025) user guide Eq. 1; docs/theory/dem_contact_laws.md §2.2, §3.1"}},
      .renamed = {},
  });
  return table;
}

std::string registry_keywords() {
  std::string list;
  for (const auto& info : contact_law_registry()) list += (list.empty() ? "\"" : ", \"") + info.keyword + "\" (" + info.summary + ")";
  return list;
}

}  // namespace

const std::vector<ContactLawInfo>& contact_law_registry() {
  static const std::vector<ContactLawInfo> table = build_registry();
  return table;
}

const ContactLawInfo* find_contact_law(std::string_view keyword) noexcept {
  for (const auto& info : contact_law_registry())
    if (info.keyword == keyword) return &info;
  return nullptr;
}

bool ContactLawSetting::intact_force_from_history() const {
  return std::visit(
      [](const auto& l) {
        using Law = std::decay_t<decltype(l)>;
        if constexpr (requires { Law::intact_force_from_history; }) return Law::intact_force_from_history;
        else return false;
      },
      law);
}

std::size_t ContactLawSetting::history_size() const {
  return std::visit([](const auto& l) { return std::decay_t<decltype(l)>::history_size; }, law);
}

std::size_t ContactLawSetting::cold_history_size() const {
  return std::visit([](const auto& l) { return cold_history_size_of<std::decay_t<decltype(l)>>(); }, law);
}

bool ContactLawSetting::has_couple() const {
  return std::visit([](const auto& l) { return std::decay_t<decltype(l)>::has_couple; }, law);
}

StiffnessBound ContactLawSetting::stiffness_bound(double radius_max) const {
  return std::visit([radius_max](const auto& l) { return l.stiffness_bound(radius_max); }, law);
}

bool ContactLawSetting::bonded() const {
  return std::visit([](const auto& l) { return std::decay_t<decltype(l)>::bonded; }, law);
}

double ContactLawSetting::bond_gap() const {
  return std::visit([](const auto& l) {
    if constexpr (std::decay_t<decltype(l)>::bonded) return l.bond_gap;
    else return 0.0;
  }, law);
}

bool ContactLawSetting::can_add_bond_load() const {
  return std::visit([](const auto& l) { return requires(double* h, const ContactKinematics& k, const Vec3& f) { l.add_bond_load(h, k, f); }; }, law);
}

void ContactLawSetting::add_bond_load(double* history, const ContactKinematics& k, const Vec3& force_on_first) const {
  std::visit(
      [&](const auto& l) {
        if constexpr (requires { l.add_bond_load(history, k, force_on_first); }) l.add_bond_load(history, k, force_on_first);
        else throw std::logic_error("contact law \"" + info->keyword + "\" cannot take a load onto a bond");
      },
      law);
}

ContactLawSetting read_contact_law(ConfigReader section) {
  // A law's key that another law reads with another meaning: refused by name
  // before the declared reader would call it merely unknown (an undeclared
  // reader of the same object, whatever `section` follows).
  ConfigReader given(section.object(), section.path());
  const std::string given_keyword = given.has("law") ? given.string("law") : std::string(LinearLaw::keyword);
  if (const ContactLawInfo* given_info = find_contact_law(given_keyword))
    for (const auto& old : given_info->renamed)
      if (given.has(old.key))
        given.fail(old.key, "law \"" + given_keyword + "\" reads this value as \"" + old.renamed_to + "\": " + old.why + "; rename the key to \"" +
                                old.renamed_to + "\" (same value, same results)");
  if (find_contact_law(given_keyword) == nullptr)
    given.fail("law", "unknown contact law \"" + given_keyword + "\"; the registry has " + registry_keywords());
  ConfigReader cfg = section.declared_as_section(sections::dem_contact());
  const std::string keyword = cfg.string("law");
  const ContactLawInfo* info = find_contact_law(keyword);
  if (info == nullptr) cfg.fail("law", "unknown contact law \"" + keyword + "\"; the registry has " + registry_keywords());
  ContactLawSetting setting;
  setting.info = info;
  for (const auto& parameter : info->parameters) setting.values.push_back(cfg.number(parameter.key));
  cfg.finish();
  setting.law = info->make(LawParameters(info->parameters, setting.values));
  return setting;
}

ContactLawSetting make_contact_law(const nlohmann::json& object, const std::string& path) {
  return read_contact_law(ConfigReader(object, path));
}

ContactLawSetting upscale(const ContactLawSetting& setting, double scale_factor) {
  if (!(scale_factor > 0.0)) throw UserError("the particle upscaling factor S must be positive");
  ContactLawSetting out = setting;
  for (std::size_t k = 0; k < out.values.size(); ++k)
    out.values[k] *= std::pow(scale_factor, setting.info->parameters[k].upscaling_exponent);
  out.law = setting.info->make(LawParameters(out.info->parameters, out.values));
  return out;
}

std::string describe_contact_laws() {
  std::ostringstream out;
  for (const auto& info : contact_law_registry()) {
    out << "  law \"" << info.keyword << "\": " << info.summary << "\n"
        << "    source: " << info.reference << "\n"
        << "    upscaling by S: " << info.upscaling_rule << "\n";
    for (const auto& s : info.stiffness) out << "    stiffness: " << s.key << " sets " << s.formula << " (" << s.source << ")\n";
    for (const auto& r : info.renamed) out << "    " << r.key << ": renamed " << r.renamed_to << " (refused: " << r.why << ")\n";
    // Each parameter's unit, default and meaning are in the section tree above
    // (the contact section's law variants, from the same declarations): named here only.
    out << "    parameters:";
    for (const auto& p : info.parameters) out << " " << p.key;
    out << "\n";
    out << "    per-contact history:";
    for (const auto& h : info.history) out << " " << h.name << " [" << h.unit << "]";
    out << "\n";
  }
  return out.str();
}

LawParameters::LawParameters(std::span<const ParameterDeclaration> declared, std::span<const double> values)
    : declared_(declared), values_(values) {
  if (declared.size() != values.size()) throw std::logic_error("a law's values do not match its declaration");
}

double LawParameters::operator[](std::string_view key) const {
  for (std::size_t k = 0; k < declared_.size(); ++k)
    if (declared_[k].key == key) return values_[k];
  throw std::logic_error("a contact law reads \"" + std::string(key) + "\", which its declaration lacks (dfc/common/sections/dem_contact_laws.hpp)");
}

}  // namespace dfc::dem
