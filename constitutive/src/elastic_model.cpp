#include "dfc/constitutive/elastic_model.hpp"

#include "dfc/common/config_reader.hpp"

namespace dfc::constitutive {

ElasticModuli moduli_from_young_poisson(double young_modulus, double poisson_ratio) {
  return {young_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)), young_modulus / (2.0 * (1.0 + poisson_ratio))};
}

ElasticModuli read_elastic_moduli(ConfigReader& material) {
  const bool young_given = material.has("young_modulus_pa") || material.has("poisson_ratio");
  const bool bulk_given = material.has("bulk_modulus_pa") || material.has("shear_modulus_pa");
  if (young_given && bulk_given)
    material.fail("bulk_modulus_pa", "give either young_modulus_pa + poisson_ratio or bulk_modulus_pa + shear_modulus_pa, not both");
  if (bulk_given) {
    const double bulk = material.number("bulk_modulus_pa");
    const double shear = material.number("shear_modulus_pa");
    return {bulk, shear};
  }
  const double young = material.number("young_modulus_pa");
  const double poisson = material.number("poisson_ratio");
  if (!(poisson < 0.5))
    material.fail("poisson_ratio", "expected a number in (-1, 0.5), got 0.5 (incompressible; the bulk modulus would be infinite)");
  return moduli_from_young_poisson(young, poisson);
}

Stress elastic_stress_increment(const ElasticModuli& moduli, const SymTensor& strain_increment) {
  return 2.0 * moduli.shear * strain_increment.deviator() + SymTensor::isotropic(moduli.bulk * strain_increment.trace());
}

ElasticModel::ElasticModel(ElasticModuli moduli) : moduli_(moduli) {}

ElasticModel ElasticModel::from_young_poisson(double young_modulus, double poisson_ratio) {
  return ElasticModel(moduli_from_young_poisson(young_modulus, poisson_ratio));
}

std::unique_ptr<ConstitutiveModel> ElasticModel::from_config(ConfigReader& material) {
  return std::make_unique<ElasticModel>(read_elastic_moduli(material));
}

void ElasticModel::update(const StrainIncrement& increment, Stress& stress, StateSpan /*state*/) const {
  stress += elastic_stress_increment(moduli_, increment.strain);
}

}  // namespace dfc::constitutive
