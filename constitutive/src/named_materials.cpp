#include "dfc/constitutive/named_materials.hpp"

#include <algorithm>
#include <array>

namespace dfc::constitutive {

namespace {

// Ciantia et al. 2024 Table 2 (Saint Nicholas at Wade chalk, structured Cam Clay):
// E = 1 GPa, ν = 0.12, p_s0 = 3000 kPa, p_t0 = 200 kPa, ρ_s = 19, ρ_t = 15,
// ξ_s = ξ_t = 0.5, M_f = 1.0, M_g = 1.2; ρ' = 1.4 Mg/m³ → density 1400 kg/m³.
// e_0 = 0.83 is not a parameter of this formulation (the elastic law is given
// by E and ν, and p_s hardens through ρ_s directly); k is not in Table 2 and
// keeps the model default 0 (docs/fdm_models.md).
constexpr std::string_view kChalkSnw = R"({
  "model": "structured_cam_clay", "density_kg_m3": 1400,
  "young_modulus_pa": 1.0e9, "poisson_ratio": 0.12,
  "ps0_pa": 3.0e6, "pt0_pa": 2.0e5, "mf": 1.0, "mg": 1.2,
  "rho_s": 19, "rho_t": 15, "xi_s": 0.5, "xi_t": 0.5
})";

const std::array<NamedMaterial, 1> kNamedMaterials = {{
    {"chalk_snw", "Ciantia et al. 2024 Table 2: Saint Nicholas at Wade chalk, structured Cam Clay", kChalkSnw},
}};

}  // namespace

std::span<const NamedMaterial> named_materials() { return kNamedMaterials; }

const NamedMaterial* find_named_material(std::string_view name) {
  const auto it = std::find_if(kNamedMaterials.begin(), kNamedMaterials.end(), [&](const NamedMaterial& m) { return m.name == name; });
  return it == kNamedMaterials.end() ? nullptr : &*it;
}

nlohmann::json expand_named_material(const NamedMaterial& preset, const nlohmann::json& overrides) {
  nlohmann::json material = nlohmann::json::parse(preset.material);
  for (const auto& [key, value] : overrides.items())
    if (key != "preset") material[key] = value;
  return material;
}

std::string describe_named_materials() {
  std::string text;
  for (const NamedMaterial& m : kNamedMaterials) {
    text += "  \"" + std::string(m.name) + "\": " + std::string(m.source) + "\n      ";
    text += nlohmann::json::parse(m.material).dump() + "\n";
  }
  return text;
}

}  // namespace dfc::constitutive
