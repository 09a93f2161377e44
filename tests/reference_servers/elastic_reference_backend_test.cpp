// ElasticReferenceBackend as a protocol backend: what it refuses, and the
// provider contract of its advance (velocity carries the partner's interface
// to the static displacement over the advance).
#include <gtest/gtest.h>

#include "dfc/common/errors.hpp"
#include "dfc/reference/elastic_reference_backend.hpp"
#include "reference_test_support.hpp"

namespace dfc::reference {
namespace {

std::string config_error_key(const nlohmann::json& section) {
  ElasticReferenceBackend backend;
  try {
    (void)backend.configure(section);
  } catch (const ConfigError& e) {
    return e.key_path();
  }
  return "(accepted)";
}

TEST(ElasticReferenceBackend, RefusesNonElasticModelsNamingTheKey) {
  nlohmann::json section = test::pile_continuum_section();
  section["material"] = {{"model", "mohr_coulomb"}, {"density_kg_m3", 2000}, {"young_modulus_pa", 5e7}, {"poisson_ratio", 0.25},
                         {"cohesion_pa", 1e4}, {"friction_angle_deg", 30}, {"tensile_strength_pa", 1e4}};
  EXPECT_EQ(config_error_key(section), "material.model");
}

TEST(ElasticReferenceBackend, RefusesTheDrivenRoleAndAnUnsupportedBody) {
  nlohmann::json driven = test::pile_continuum_section();
  driven["coupling"]["role"] = "driven";
  EXPECT_EQ(config_error_key(driven), "coupling.role");
  nlohmann::json floating = test::pile_continuum_section();
  floating.erase("boundaries");
  EXPECT_EQ(config_error_key(floating), "boundaries");
}

TEST(ElasticReferenceBackend, VelocityCarriesTheInterfaceToTheStaticDisplacement) {
  ElasticReferenceBackend backend;
  (void)backend.configure(test::pile_continuum_section());
  const protocol::InterfaceMesh mesh = backend.interface_mesh();
  const std::int64_t n = mesh.node_count();
  const auto advance = [&](double fx) {
    std::vector<double> force(std::size_t(3 * n), 0.0);
    for (std::int64_t r = 0; r < n; ++r) force[std::size_t(3 * r)] = fx;
    protocol::AdvanceRequest request;
    request.n_steps = 4;
    request.dt = 1e-5;
    request.inputs.push_back(protocol::Array::from_f64(protocol::field::force, {n, 3}, force));
    return backend.advance(request);
  };
  const protocol::AdvanceResult first = advance(0.0);
  const protocol::AdvanceResult second = advance(2.0);
  const auto u1 = protocol::require_f64(first.outputs, protocol::field::displacement, n, 3);
  const auto u2 = protocol::require_f64(second.outputs, protocol::field::displacement, n, 3);
  const auto v1 = protocol::require_f64(first.outputs, protocol::field::velocity, n, 3);
  const auto v2 = protocol::require_f64(second.outputs, protocol::field::velocity, n, 3);
  double largest_step = 0.0;
  for (std::size_t k = 0; k < u1.size(); ++k) {
    // Displacements are relative to the initial state, which the first advance leaves.
    EXPECT_DOUBLE_EQ(v1[k] * 4e-5, u1[k]);
    EXPECT_NEAR(v2[k] * 4e-5, u2[k] - u1[k], 1e-12 * std::abs(u2[k]) + 1e-300);
    largest_step = std::max(largest_step, std::abs(u2[k] - u1[k]));
  }
  EXPECT_GT(largest_step, 0.0) << "a 2 N load per node must move the wall";
  EXPECT_EQ(second.monitors["interface_force_received"][0].get<double>(), 2.0 * double(n));
  EXPECT_EQ(second.monitors["step"].get<std::int64_t>(), 8);
}

}  // namespace
}  // namespace dfc::reference
