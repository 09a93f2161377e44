#pragma once
// The contact-law registry: keyword -> law (CONTRIBUTING.md §2: "one registry
// table per plug-in family"). Parsing, --help text and upscaling all read the
// same table, so a law is documented where it is declared.
//
// Adding a law: write the law type (see linear_law.hpp and ContactLawKernel),
// add it to the ContactLaw variant below and one entry to the table in
// contact_law_registry.cpp. Nothing else changes.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/common/config_reader.hpp"
#include "dfc/dem/contact_model.hpp"
#include "dfc/dem/damage_bond_law.hpp"
#include "dfc/dem/linear_law.hpp"
#include "dfc/dem/linear_pbond_law.hpp"
#include "dfc/dem/soft_bond_law.hpp"

namespace dfc::dem {

/// Every law the kernels are compiled for. Dispatch: std::visit once per step.
using ContactLaw = std::variant<LinearLaw, LinearPbondLaw, SoftBondLaw, DamageBondLaw>;

/// Which stiffness one modulus (or stiffness) key of a law sets, stated once
/// for --help, docs/dem_bond_laws.md and the test that checks it against the
/// law's force (tests/dem/law_stiffness_test.cpp).
struct StiffnessMeaning {
  std::string key;      ///< the parameter, e.g. "emod_pa"
  std::string formula;  ///< e.g. "k_n = pi E* R_min^2/(R1+R2) [N/m], k_s = k_n/kratio"
  std::string source;   ///< paper (and equation) the formula comes from
};

/// A key the law once read with a meaning another law gives it: refused with
/// a keyed error naming the new key, never read silently.
struct RenamedKey {
  std::string key;         ///< the old name
  std::string renamed_to;  ///< the new name (same value, same result)
  std::string why;         ///< what the old name would be misread as
};

struct ContactLawInfo {
  std::string keyword;
  std::string summary;         ///< one line
  std::string reference;       ///< where the equations come from
  std::string upscaling_rule;  ///< one sentence: what stays fixed, what scales with S
  std::vector<ParameterDeclaration> parameters;  ///< the law's declaration (dfc/common/sections/dem_contact_laws.hpp)
  std::vector<HistoryColumn> history;
  ContactLaw (*make)(const LawParameters& values) = nullptr;
  std::vector<StiffnessMeaning> stiffness;  ///< one per modulus or stiffness key
  std::vector<RenamedKey> renamed;
};

[[nodiscard]] const std::vector<ContactLawInfo>& contact_law_registry();
/// nullptr if no law has this keyword.
[[nodiscard]] const ContactLawInfo* find_contact_law(std::string_view keyword) noexcept;

/// A law chosen and parameterised by a scenario.
struct ContactLawSetting {
  const ContactLawInfo* info = nullptr;
  std::vector<double> values;  ///< in info->parameters order
  ContactLaw law;

  /// Doubles of history per contact, a whole row (the archive's, a snapshot's columns).
  [[nodiscard]] std::size_t history_size() const;
  /// The last columns of a row a pair keeps in its second row (contact_model.hpp SplitsHistory); 0 for most laws.
  [[nodiscard]] std::size_t cold_history_size() const;
  [[nodiscard]] bool has_couple() const;
  /// For particles of radius up to radius_max (m): deformability laws scale with R.
  [[nodiscard]] StiffnessBound stiffness_bound(double radius_max) const;
  /// Bonded laws keep a BondState in history column 0 (bond_state.hpp).
  [[nodiscard]] bool bonded() const;
  /// True for laws whose intact bond carries its whole force in stored history
  /// (no overlap term): their bonded states can be scaled (stress_scaling.hpp).
  [[nodiscard]] bool intact_force_from_history() const;
  /// m, bonding gap of a bonded law (pairs with surface gap <= it are bonded at start); 0 otherwise.
  [[nodiscard]] double bond_gap() const;
  /// True for laws that can take a load onto a bond with its matching
  /// displacement (Law::add_bond_load; the seam balance, seam_balance.hpp).
  [[nodiscard]] bool can_add_bond_load() const;
  /// Law::add_bond_load on one bonded contact's history; std::logic_error for
  /// a law without it (check can_add_bond_load first).
  void add_bond_load(double* history, const ContactKinematics& k, const Vec3& force_on_first) const;
};

/// Reads {"law": keyword (default "linear"), <parameters>...} and finishes the
/// object. Unknown law -> ConfigError on "<path>.law" listing the registry.
[[nodiscard]] ContactLawSetting read_contact_law(ConfigReader cfg);
/// The same from a JSON object, e.g. {"law":"linear","kn_n_m":1e5,"ks_n_m":1e5};
/// key paths in errors start at `path`.
[[nodiscard]] ContactLawSetting make_contact_law(const nlohmann::json& object, const std::string& path = "contact");

/// Parameters of `setting` for particles upscaled by S (> 0): p * S^exponent.
[[nodiscard]] ContactLawSetting upscale(const ContactLawSetting& setting, double scale_factor);

/// Human-readable table of the registry (for --help).
[[nodiscard]] std::string describe_contact_laws();

}  // namespace dfc::dem
