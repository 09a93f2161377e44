#pragma once
// Particle materials: one contact-law parameter set per material, and the
// parameter set of every pair of materials (docs/dem_generation.md §7).
//
// A graded model (particle upscaling that varies in space; Ciantia,
// Previtali, Zheng et al. 2024, §3: S = 2.1 near the pile rising to 4.8)
// gives each zone its own material: the same law with the parameters
// upscaled by the zone's S (contact_law_registry.hpp upscale). A pair of
// particles of materials a and b acts with the mixed set mix(a, b), as
// LAMMPS's pair styles mix coefficients of unlike types (pair_coeff's
// "mix" rules, e.g. the geometric rule of pair lj/cut):
//   - a parameter with an upscaling exponent e != 0 (it scales as S^e):
//     the geometric mean sqrt(p_a p_b). For sets upscaled from one set by
//     S_a and S_b this is exactly the set at S = sqrt(S_a S_b) (the
//     parameter is p_1 S^e), so the mixing rule is itself an upscaling;
//   - a parameter that does not scale (moduli, strengths, ratios,
//     friction): the arithmetic mean, which keeps equal values equal.
// A pair of one material uses that material's set unchanged (bit for bit).
// All materials use one law (one history layout per pair list): a pair of
// different laws has no defined mixture.
#include <cstddef>
#include <cstdint>
#include <variant>
#include <vector>

#include "dfc/dem/contact_law_registry.hpp"

namespace dfc::dem {

/// std::variant<std::vector<L>...> for ContactLaw = std::variant<L...>: a
/// table of laws of one type, visited once per step like ContactLaw.
template <class Variant>
struct VectorsOfAlternatives;
template <class... Laws>
struct VectorsOfAlternatives<std::variant<Laws...>> {
  using type = std::variant<std::vector<Laws>...>;
};
using ContactLawTable = VectorsOfAlternatives<ContactLaw>::type;

/// The mixed parameter set of a pair of materials (rule above). UserError if
/// the two use different laws.
[[nodiscard]] ContactLawSetting mix_contact_laws(const ContactLawSetting& a, const ContactLawSetting& b);

using MaterialId = std::uint16_t;

class ParticleMaterials {
 public:
  /// `materials[m]` is material m's law; at least one. UserError if they do
  /// not all use one law or there are more than max_count.
  explicit ParticleMaterials(std::vector<ContactLawSetting> materials);

  static constexpr std::size_t max_count = 256;

  [[nodiscard]] std::size_t count() const noexcept { return materials_.size(); }
  [[nodiscard]] const ContactLawSetting& material(std::size_t m) const { return materials_.at(m); }
  /// Index into pair_setting() / pair_laws() of a pair of materials a, b (symmetric).
  [[nodiscard]] std::size_t pair_index(MaterialId a, MaterialId b) const noexcept { return std::size_t(a) * materials_.size() + b; }
  [[nodiscard]] const ContactLawSetting& pair_setting(std::size_t index) const { return pairs_.at(index); }
  /// The pair laws in pair_index order (count() x count()).
  [[nodiscard]] const ContactLawTable& pair_laws() const noexcept { return table_; }
  /// m, the largest bonding gap of any pair of materials.
  [[nodiscard]] double largest_bond_gap() const noexcept;
  /// The stiffest of the pair laws for radii up to radius_max (critical time step).
  [[nodiscard]] StiffnessBound stiffness_bound(double radius_max) const;

 private:
  std::vector<ContactLawSetting> materials_;
  std::vector<ContactLawSetting> pairs_;  ///< count() x count(), symmetric
  ContactLawTable table_;
};

}  // namespace dfc::dem
