// FdmBackend: the protocol face of the solver (interface mesh, matching,
// input validation, determinism, snapshot layout).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <set>

#include "dfc/fdm/fdm_backend.hpp"

namespace dfc::fdm {
namespace {

using protocol::AdvanceRequest;
using protocol::Array;
using protocol::ErrorCode;
using protocol::ProtocolError;

nlohmann::json box_section(const std::string& role, const std::string& group) {
  nlohmann::json section = nlohmann::json::parse(R"({
    "mesh": {"type": "box", "size_m": [1, 1, 1], "zones": [2, 3, 2]},
    "material": {"model": "elastic", "density_kg_m3": 2000, "bulk_modulus_pa": 1e7, "shear_modulus_pa": 5e6},
    "gravity_m_s2": [0, 0, -9.81],
    "threads": 1,
    "boundaries": [{"group": "zmin", "condition": "fixed"}]
  })");
  if (!role.empty()) section["coupling"] = {{"role", role}, {"group", group}};
  return section;
}

ErrorCode error_code_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const ProtocolError& e) {
    return e.code();
  }
  ADD_FAILURE() << "no ProtocolError";
  return ErrorCode::internal;
}

AdvanceRequest request(std::int64_t n_steps, double dt, std::vector<Array> inputs) { return {0, n_steps, dt, std::move(inputs)}; }

TEST(FdmBackend, IdentityAndConfigureInfo) {
  FdmBackend backend;
  const auto id = backend.identity();
  EXPECT_EQ(id.name, "fdm_server");
  EXPECT_EQ(id.role, "continuum");
  const nlohmann::json info = backend.configure(box_section("", ""));
  EXPECT_EQ(info["gridpoints"], 3 * 4 * 3);
  EXPECT_EQ(info["zones"], 2 * 3 * 2);
  EXPECT_GT(info["dt_suggested"].get<double>(), 0.0);
  EXPECT_TRUE(info["dt_max"].is_null());  // mass scaling on by default
  EXPECT_EQ(info["capabilities"], nlohmann::json::array({"snapshot", "checkpoint"}));  // standalone: no interface
  nlohmann::json real_masses = box_section("", "");
  real_masses["mass_scaling"] = false;
  FdmBackend dynamic;
  EXPECT_DOUBLE_EQ(dynamic.configure(real_masses)["dt_max"].get<double>(), info["dt_suggested"].get<double>());
}

TEST(FdmBackend, ProviderInterfaceHasTwoTrianglesPerQuadAndUniqueIds) {
  FdmBackend backend;
  const nlohmann::json info = backend.configure(box_section("provider", "zmax"));
  EXPECT_EQ(info["capabilities"], nlohmann::json::array({"provides_interface", "snapshot", "checkpoint"}));
  const protocol::InterfaceMesh mesh = backend.interface_mesh();
  EXPECT_EQ(mesh.facet_count(), 2 * 2 * 3);  // 2 × (2 × 3 quads)
  EXPECT_EQ(mesh.node_count(), 3 * 4);
  EXPECT_EQ(std::set<std::int64_t>(mesh.node_ids.begin(), mesh.node_ids.end()).size(), mesh.node_ids.size());
  for (std::int64_t f = 0; f < mesh.facet_count(); ++f) {
    std::array<Vec3, 3> x;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto r = std::size_t(mesh.facets[std::size_t(3 * f) + k]);
      ASSERT_LT(r, mesh.node_ids.size());
      x[k] = Vec3(mesh.coordinates[3 * r], mesh.coordinates[3 * r + 1], mesh.coordinates[3 * r + 2]);
    }
    EXPECT_GT((x[1] - x[0]).cross(x[2] - x[0]).z(), 0.0) << "facet " << f << " must face out of the continuum (+z)";
  }
  EXPECT_EQ(error_code_of([&] { backend.set_interface(mesh); }), ErrorCode::unsupported);
}

TEST(FdmBackend, DrivenMatchingRejectsANodeOffTheGroup) {
  FdmBackend provider;
  provider.configure(box_section("provider", "zmax"));
  protocol::InterfaceMesh mesh = provider.interface_mesh();
  FdmBackend driven;
  driven.configure(box_section("driven", "zmax"));
  EXPECT_NO_THROW(driven.set_interface(mesh));
  mesh.node_ids[2] = 777;
  mesh.coordinates[3 * 2 + 2] -= 0.25;  // node moved below the face
  try {
    driven.set_interface(mesh);
    FAIL() << "an off-group node was matched";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_array);
    EXPECT_NE(std::string(e.what()).find("id 777"), std::string::npos) << e.what();
  }
}

TEST(FdmBackend, AdvanceWithWrongArrayShapeIsBadArray) {
  FdmBackend provider;
  provider.configure(box_section("provider", "zmax"));
  const std::int64_t n = provider.interface_mesh().node_count();
  const std::vector<double> wrong(std::size_t(2 * n), 0.0);
  EXPECT_EQ(error_code_of([&] { provider.advance(request(1, 1.0, {Array::from_f64("force", {n, 2}, wrong)})); }), ErrorCode::bad_array);
  EXPECT_EQ(error_code_of([&] { provider.advance(request(1, 1.0, {})); }), ErrorCode::bad_array);  // force missing
  const std::vector<double> force(std::size_t(3 * n), 0.0);
  EXPECT_EQ(error_code_of([&] {
              provider.advance(request(1, 1.0, {Array::from_f64("force", {n, 3}, force), Array::from_f64("mass", {n, 3}, force)}));
            }),
            ErrorCode::bad_array);
  FdmBackend standalone;
  standalone.configure(box_section("", ""));
  EXPECT_EQ(error_code_of([&] { standalone.advance(request(1, 1.0, {Array::from_f64("force", {n, 3}, force)})); }), ErrorCode::bad_array);
  FdmBackend driven;
  driven.configure(box_section("driven", "zmax"));
  EXPECT_EQ(error_code_of([&] { driven.advance(request(1, 1.0, {Array::from_f64("velocity", {n, 3}, force)})); }), ErrorCode::out_of_order);
}

std::vector<double> provider_run(int threads) {
  FdmBackend backend;
  nlohmann::json section = box_section("provider", "zmax");
  section["threads"] = threads;
  backend.configure(section);
  const std::int64_t n = backend.interface_mesh().node_count();
  std::vector<double> force(std::size_t(3 * n));
  for (std::size_t i = 0; i < force.size(); ++i) force[i] = 10.0 * std::sin(double(i));
  std::vector<double> displacement;
  for (int exchange = 0; exchange < 20; ++exchange) {
    const auto result = backend.advance(request(5, 0.5, {Array::from_f64("force", {n, 3}, force)}));
    displacement = protocol::find_array(result.outputs, "displacement")->to_f64();
  }
  return displacement;
}

TEST(FdmBackend, IdenticalRunsAreBitIdentical) {
  const std::vector<double> a = provider_run(1);
  const std::vector<double> b = provider_run(1);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  EXPECT_GT(*std::max_element(a.begin(), a.end()), 0.0);  // something moved
}

std::vector<double> standalone_displacements(int threads) {
  // 14³ zones: above the solver's threshold for parallel passes.
  nlohmann::json section = box_section("", "");
  section["mesh"]["zones"] = {14, 14, 14};
  section["threads"] = threads;
  FdmBackend backend;
  backend.configure(section);
  backend.advance(request(20, 1.0, {}));
  std::string kind;
  return protocol::find_array(backend.snapshot(kind), "node_displacement")->to_f64();
}

TEST(FdmBackend, ThreadCountDoesNotChangeResults) {
  // Forces are gathered per gridpoint in a fixed order, so results are bit-identical for any thread count.
  const std::vector<double> serial = standalone_displacements(1);
  const std::vector<double> parallel = standalone_displacements(2);
  ASSERT_EQ(serial.size(), parallel.size());
  EXPECT_EQ(std::memcmp(serial.data(), parallel.data(), serial.size() * sizeof(double)), 0);
}

TEST(FdmBackend, ProviderMonitorsReportReceivedForceAndPower) {
  FdmBackend backend;
  backend.configure(box_section("provider", "zmax"));
  const std::int64_t n = backend.interface_mesh().node_count();
  std::vector<double> force(std::size_t(3 * n), 0.0);
  for (std::size_t r = 0; r < std::size_t(n); ++r) force[3 * r + 2] = -2.0;  // pushing down
  const auto result = backend.advance(request(3, 1.0, {Array::from_f64("force", {n, 3}, force)}));
  EXPECT_DOUBLE_EQ(result.monitors["interface_force_received"][2].get<double>(), -2.0 * double(n));
  EXPECT_GT(result.monitors["interface_power_w"].get<double>(), 0.0);  // the load does work on a body moving down
  EXPECT_EQ(result.monitors["step"], 3);
  EXPECT_TRUE(result.monitors.contains("unbalanced_force_ratio"));
  EXPECT_TRUE(result.monitors.contains("kinetic_energy_j"));
}

TEST(FdmBackend, SnapshotCarriesTheCouplingForceOnEachInterfaceNode) {
  // node_external_force: the force each interface node received, at that
  // node's position, zero elsewhere; its sum is the monitor's.
  FdmBackend backend;
  backend.configure(box_section("provider", "zmax"));
  const protocol::InterfaceMesh& mesh = backend.interface_mesh();
  const std::int64_t n = mesh.node_count();
  std::vector<double> force(std::size_t(3 * n));
  for (std::size_t r = 0; r < std::size_t(n); ++r) {
    force[3 * r] = 0.5 * double(r + 1);
    force[3 * r + 1] = -0.25 * double(r);
    force[3 * r + 2] = -2.0 - double(r);
  }
  const auto result = backend.advance(request(1, 1e-4, {Array::from_f64("force", {n, 3}, force)}));
  std::string kind;
  const std::vector<Array> arrays = backend.snapshot(kind);
  const Array* external = protocol::find_array(arrays, "node_external_force");
  ASSERT_NE(external, nullptr);
  const auto positions = protocol::find_array(arrays, "node_position")->to_f64();
  const auto values = external->to_f64();
  ASSERT_EQ(values.size(), positions.size());
  std::size_t loaded = 0;
  Vec3 sum = Vec3::Zero();
  for (std::size_t gp = 0; gp < values.size() / 3; ++gp) {
    const Vec3 f(values[3 * gp], values[3 * gp + 1], values[3 * gp + 2]);
    if (f.isZero(0.0)) continue;
    ++loaded;
    sum += f;
    // The interface row with this gridpoint's position carries the same force.
    bool matched = false;
    for (std::size_t r = 0; r < std::size_t(n); ++r) {
      const Vec3 at(mesh.coordinates[3 * r], mesh.coordinates[3 * r + 1], mesh.coordinates[3 * r + 2]);
      if ((at - Vec3(positions[3 * gp], positions[3 * gp + 1], positions[3 * gp + 2])).norm() > 1e-12) continue;
      matched = true;
      EXPECT_EQ(f, Vec3(force[3 * r], force[3 * r + 1], force[3 * r + 2])) << "gridpoint " << gp;
    }
    EXPECT_TRUE(matched) << "a force on gridpoint " << gp << ", which is not on the interface";
  }
  EXPECT_EQ(loaded, std::size_t(n));
  for (Eigen::Index c = 0; c < 3; ++c)
    EXPECT_NEAR(sum[c], result.monitors["interface_force_received"][std::size_t(c)].get<double>(), 1e-12 * double(n * n));
}

TEST(FdmBackend, SnapshotUsesVtkHexahedronOrder) {
  FdmBackend backend;
  backend.configure(box_section("", ""));
  std::string kind;
  const std::vector<Array> arrays = backend.snapshot(kind);
  EXPECT_EQ(kind, "grid");
  const Array* zones = protocol::find_array(arrays, "zone_nodes");
  const Array* positions = protocol::find_array(arrays, "node_position");
  const Array* stress = protocol::find_array(arrays, "zone_stress");
  ASSERT_TRUE(zones && positions && stress);
  EXPECT_EQ(zones->shape, (std::vector<std::int64_t>{12, 8}));
  EXPECT_EQ(stress->shape, (std::vector<std::int64_t>{12, 6}));
  const auto nodes = zones->to_i64();
  const auto x = positions->to_f64();
  // VTK_HEXAHEDRON: 0(000) 1(100) 2(110) 3(010) 4(001) 5(101) 6(111) 7(011), relative to corner 0.
  const std::array<std::array<int, 3>, 8> vtk = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  const Vec3 zone_size(0.5, 1.0 / 3.0, 0.5);
  const auto point = [&](std::int64_t gp) { return Vec3(x[std::size_t(3 * gp)], x[std::size_t(3 * gp + 1)], x[std::size_t(3 * gp + 2)]); };
  for (std::size_t k = 0; k < 8; ++k) {
    const Vec3 offset = point(nodes[k]) - point(nodes[0]);
    for (Eigen::Index c = 0; c < 3; ++c) EXPECT_NEAR(offset[c], vtk[k][std::size_t(c)] * zone_size[c], 1e-12) << "corner " << k;
  }
}

}  // namespace
}  // namespace dfc::fdm
