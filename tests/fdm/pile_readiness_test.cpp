// Readiness of the continuum for the pile problem (Ciantia et al. 2024 Fig. 1): the
// cylinder around the DEM cavity is graded towards the interface and passes
// the quality checks, and the geostatic state at N·g with K0 is in equilibrium
// (unbalanced-force ratio < 1e-5, FLAC's default) before coupling starts, both
// with the cavity wall held and with the wall loaded by the in-situ traction
// the DEM region exerts when coupling begins.
#include <gtest/gtest.h>

#include <cmath>

#include "dfc/common/errors.hpp"
#include "dfc/fdm/fdm_backend.hpp"
#include "dfc/fdm/fdm_config.hpp"
#include "dfc/fdm/mesh_generators.hpp"
#include "dfc/fdm/mesh_quality.hpp"

namespace dfc::fdm {
namespace {

constexpr double kG = 9.81;
constexpr double kN = 100.0;  // centrifuge acceleration level
constexpr double kK0 = 0.6;
constexpr double kDensity = 1400.0;  // chalk_snw
constexpr double kRatio = 1e-5;      // §1.11, FLAC's default equilibrium ratio

// The 100 mm × 120 mm chalk cylinder of Ciantia et al. 2024 around a 20 mm-radius DEM cavity.
nlohmann::json pile_section(const std::string& inner_wall) {
  nlohmann::json section = nlohmann::json::parse(R"({
    "mesh": {"type": "cylinder_cavity", "inner_radius_m": 0.02, "outer_radius_m": 0.05, "height_m": 0.12,
             "zones_radial": 8, "zones_around": 32, "zones_vertical": 24, "grading_ratio": 1.15},
    "material": {"preset": "chalk_snw"},
    "threads": 1,
    "boundaries": [{"group": "bottom", "condition": "fixed"}, {"group": "outer", "condition": "roller"}],
    "initial_stress": {"type": "geostatic", "k0": 0.6}
  })");
  section["gravity_m_s2"] = {0.0, 0.0, -kN * kG};
  if (inner_wall == "roller") section["boundaries"].push_back({{"group", "inner"}, {"condition", "roller"}});
  if (inner_wall == "provider") section["coupling"] = {{"role", "provider"}, {"group", "inner"}};
  return section;
}

TEST(PileReadiness, CavityMeshIsGradedTowardsTheInterfaceAndPassesTheQualityChecks) {
  const FdmModel model = load_fdm_model(pile_section("roller"));
  const Mesh& mesh = model.solver.mesh();
  // Radial zone size grows outwards by the grading ratio (finest at the DEM interface).
  EXPECT_LT(mesh.points[1].x() - mesh.points[0].x(), 0.5 * (mesh.points[8].x() - mesh.points[7].x()));
  double worst = 0.0;
  for (Index z = 0; z < mesh.zone_count(); ++z) worst = std::max(worst, zone_aspect_ratio(mesh, z));
  EXPECT_LE(worst, kDefaultMaxAspectRatio);
  EXPECT_NO_THROW(check_mesh_quality(mesh));
  // The same mesh with a much coarser circumference is refused, naming zones.
  nlohmann::json bad = pile_section("roller");
  bad["mesh"]["zones_around"] = 3;
  try {
    (void)load_fdm_model(bad);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.key_path(), "mesh.max_aspect_ratio");
    EXPECT_NE(std::string(e.what()).find("zones 0 (centroid"), std::string::npos) << e.what();
  }
}

TEST(PileReadiness, GeostaticStateAtNgWithK0IsInEquilibriumWithTheCavityWallHeld) {
  FdmModel model = load_fdm_model(pile_section("roller"));
  Solver& solver = model.solver;
  // The initial stress is the K0 profile at N·g: σv = ρ N g d at a zone centroid.
  const Index bottom_zone = 0;
  const double depth = 0.12 - solver.mesh().zone_centroid(bottom_zone).z();
  EXPECT_NEAR(-solver.zone_stress(bottom_zone).zz, kDensity * kN * kG * depth, 1e-9 * kDensity * kN * kG * depth);
  EXPECT_NEAR(solver.zone_stress(bottom_zone).xx, kK0 * solver.zone_stress(bottom_zone).zz, 1e-9 * kDensity * kN * kG * depth);
  for (int step = 0; step < 100; ++step) {
    solver.step(1.0);
    ASSERT_LT(solver.unbalanced_force_ratio(), kRatio) << "step " << step;
  }
  // Lumped gravity + constant zone stress is the discrete equilibrium of any
  // layered mesh (§2(c)), so the ratio is round-off, not just below 1e-5.
  EXPECT_LT(solver.unbalanced_force_ratio(), 1e-12);
}

TEST(PileReadiness, CouplingStartsInEquilibriumWhenTheDemExertsTheInSituTraction) {
  FdmBackend backend;
  (void)backend.configure(pile_section("provider"));
  const protocol::InterfaceMesh interface = backend.interface_mesh();
  // The force the DEM region in its K0 state exerts on each interface gridpoint:
  // the in-situ horizontal stress K0 ρ N g d (depth of the face centroid, i.e.
  // of its zone) on the lumped quarter of each adjacent face, pushing outwards.
  const FdmModel probe = load_fdm_model(pile_section("roller"));
  const Mesh& mesh = probe.solver.mesh();
  std::vector<Vec3> force(mesh.gridpoint_count(), Vec3::Zero());
  for (const FaceQuad& face : mesh.face_group("inner")) {
    const double sigma_h = kK0 * kDensity * kN * kG * (0.12 - mesh.face_centroid(face).z());
    const Vec3 load = -sigma_h * quad_area_vector(mesh, face);  // the outward area vector points into the cavity
    for (const Index gp : face) force[gp] += load / 4.0;
  }
  std::vector<double> rows;
  for (const std::int64_t gp : interface.node_ids) rows.insert(rows.end(), {force[gp].x(), force[gp].y(), force[gp].z()});
  protocol::AdvanceRequest request;
  request.dt = 1.0;
  request.n_steps = 10;
  request.inputs.push_back(protocol::Array::from_f64(protocol::field::force, {std::int64_t(interface.node_ids.size()), 3}, rows));
  const protocol::AdvanceResult result = backend.advance(request);
  EXPECT_LT(result.monitors.at("unbalanced_force_ratio").get<double>(), kRatio);
}

}  // namespace
}  // namespace dfc::fdm
