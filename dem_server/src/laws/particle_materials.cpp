#include "dfc/dem/particle_materials.hpp"

#include <algorithm>
#include <cmath>

#include "dfc/common/errors.hpp"

namespace dfc::dem {

ContactLawSetting mix_contact_laws(const ContactLawSetting& a, const ContactLawSetting& b) {
  if (a.info != b.info)
    throw UserError("particle materials with the laws \"" + a.info->keyword + "\" and \"" + b.info->keyword +
                    "\" cannot touch: every material of a DEM section uses one contact law");
  ContactLawSetting out = a;
  for (std::size_t k = 0; k < out.values.size(); ++k) {
    const double pa = a.values[k], pb = b.values[k];
    if (pa == pb) continue;
    out.values[k] = a.info->parameters[k].upscaling_exponent != 0.0 ? std::sqrt(pa * pb) : 0.5 * (pa + pb);
  }
  out.law = a.info->make(LawParameters(a.info->parameters, out.values));
  return out;
}

ParticleMaterials::ParticleMaterials(std::vector<ContactLawSetting> materials) : materials_(std::move(materials)) {
  if (materials_.empty()) throw UserError("a DEM section needs at least one particle material");
  if (materials_.size() > max_count)
    throw UserError("a DEM section holds at most " + std::to_string(max_count) + " particle materials, not " + std::to_string(materials_.size()));
  const std::size_t n = materials_.size();
  pairs_.reserve(n * n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) pairs_.push_back(a == b ? materials_[a] : mix_contact_laws(materials_[std::min(a, b)], materials_[std::max(a, b)]));
  table_ = std::visit(
      [&](const auto& first) {
        using Law = std::decay_t<decltype(first)>;
        std::vector<Law> laws;
        laws.reserve(pairs_.size());
        for (const auto& p : pairs_) laws.push_back(std::get<Law>(p.law));
        return ContactLawTable{std::move(laws)};
      },
      materials_.front().law);
}

double ParticleMaterials::largest_bond_gap() const noexcept {
  double gap = 0.0;
  for (const auto& p : pairs_) gap = std::max(gap, p.bond_gap());
  return gap;
}

StiffnessBound ParticleMaterials::stiffness_bound(double radius_max) const {
  StiffnessBound out;
  for (const auto& p : pairs_) {
    const StiffnessBound k = p.stiffness_bound(radius_max);
    out.normal = std::max(out.normal, k.normal);
    out.shear = std::max(out.shear, k.shear);
  }
  return out;
}

}  // namespace dfc::dem
