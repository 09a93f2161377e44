// DemBackend: the protocol face of the DEM (SPEC.md §6).
#include <gtest/gtest.h>

#include <algorithm>

#include "dfc/common/errors.hpp"
#include "dfc/dem/dem_backend.hpp"
#include "dfc/protocol/monitor_units.hpp"
#include "dfc/protocol/progress_monitors.hpp"
#include "dem_test_support.hpp"

namespace dfc::dem {
namespace {

using protocol::Array;
using protocol::ErrorCode;
using protocol::ProtocolError;

nlohmann::json bed_on_interface() { return test::cylinder_bed_under_gravity(); }

/// The continuum's top face z = 0 as 2 x 2 quads split into 8 triangles.
protocol::InterfaceMesh plate() {
  protocol::InterfaceMesh mesh;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      mesh.node_ids.push_back(100 + 3 * j + i);
      mesh.coordinates.insert(mesh.coordinates.end(), {-0.04 + 0.04 * i, -0.04 + 0.04 * j, 0.0});
    }
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const std::int64_t a = 3 * j + i, b = a + 1, c = a + 4, d = a + 3;
      mesh.facets.insert(mesh.facets.end(), {a, b, c, a, c, d});
    }
  return mesh;
}

protocol::AdvanceRequest request(std::int64_t n_steps, double dt, std::vector<Array> inputs) {
  protocol::AdvanceRequest r;
  r.n_steps = n_steps;
  r.dt = dt;
  r.inputs = std::move(inputs);
  return r;
}

Array velocities(double vz, std::int64_t rows = 9) {
  std::vector<double> v;
  for (std::int64_t k = 0; k < rows; ++k) v.insert(v.end(), {0.0, 0.0, vz});
  return Array::from_f64("velocity", {rows, 3}, v);
}

ErrorCode code_of(DemBackend& backend, const protocol::AdvanceRequest& r) {
  try {
    (void)backend.advance(r);
  } catch (const ProtocolError& e) {
    return e.code();
  }
  ADD_FAILURE() << "advance did not throw";
  return ErrorCode::internal;
}

TEST(DemBackend, AdvanceWithoutVelocityAfterSetInterfaceIsBadArray) {
  DemBackend backend;
  const nlohmann::json info = backend.configure(bed_on_interface());
  const double dt = info["dt_suggested"];
  EXPECT_LT(dt, info["dt_max"].get<double>());
  backend.set_interface(plate());
  EXPECT_EQ(code_of(backend, request(1, dt, {})), ErrorCode::bad_array);
  EXPECT_EQ(code_of(backend, request(1, dt, {velocities(0.0, 8)})), ErrorCode::bad_array);  // wrong shape
  EXPECT_THROW((void)backend.advance(request(1, 2.0 * info["dt_max"].get<double>(), {velocities(0.0)})), SolverError);
}

TEST(DemBackend, OutputForcesBalanceTheReactionOnTheParticlesAndGiveThePower) {
  DemBackend backend;
  const double dt = backend.configure(bed_on_interface())["dt_suggested"];
  backend.set_interface(plate());
  protocol::AdvanceResult result;
  for (int exchange = 0; exchange < 10; ++exchange) result = backend.advance(request(200, dt, {velocities(-1e-4)}));

  ASSERT_EQ(result.outputs.size(), 1u);
  const Array& force = result.outputs[0];
  EXPECT_EQ(force.name, "force");
  ASSERT_EQ(force.shape, (std::vector<std::int64_t>{9, 3}));
  const std::vector<double> f = force.to_f64();
  double sum[3] = {0, 0, 0}, power = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k) {
    sum[k % 3] += f[k];
    if (k % 3 == 2) power += f[k] * -1e-4;
  }
  const auto reaction = result.monitors["interface_force_reaction"].get<std::vector<double>>();
  const double scale = std::abs(reaction[2]);
  ASSERT_GT(reaction[2], 0.0);  // the plate holds the particles up...
  EXPECT_LT(sum[2], 0.0);       // ...and the particles press on the plate
  // Two independent summations (vertex shares vs. particle side): rounding only.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] + reaction[std::size_t(c)], 0.0, 1e-12 * scale) << "component " << c;
  EXPECT_NEAR(result.monitors["interface_power_w"].get<double>(), power, 1e-12 * std::abs(power));
  EXPECT_GT(power, 0.0);  // pressed-down nodes moving down: work flows into the continuum
  EXPECT_GT(result.monitors["contact_count"].get<double>(), 0.0);
  EXPECT_GT(result.monitors["total_weight_n"].get<double>(), 0.0);
}

TEST(DemBackend, SnapshotHoldsParticlesAndWalls) {
  DemBackend backend;
  const nlohmann::json info = backend.configure(bed_on_interface());
  backend.set_interface(plate());
  std::string kind;
  const auto arrays = backend.snapshot(kind);
  EXPECT_EQ(kind, "particles");
  const auto n = info["particles"].get<std::int64_t>();
  const auto shape_of = [&](const std::string& name) {
    for (const auto& a : arrays)
      if (a.name == name) return a.shape;
    return std::vector<std::int64_t>{};
  };
  EXPECT_EQ(shape_of("particle_position"), (std::vector<std::int64_t>{n, 3}));
  EXPECT_EQ(shape_of("particle_radius"), (std::vector<std::int64_t>{n}));
  EXPECT_EQ(shape_of("particle_id"), (std::vector<std::int64_t>{n}));
  EXPECT_EQ(shape_of("wall_vertices"), (std::vector<std::int64_t>{9, 3}));
  EXPECT_EQ(shape_of("wall_facets"), (std::vector<std::int64_t>{8, 3}));
  EXPECT_EQ(shape_of("wall_facet_wall"), (std::vector<std::int64_t>{8}));  // one wall: the interface
  EXPECT_EQ(shape_of("bond_particle_index"), (std::vector<std::int64_t>{}));  // an unbonded law sends no bonds
  EXPECT_EQ(backend.identity().role, "dem");
}

}  // namespace
}  // namespace dfc::dem

namespace dfc::dem {
namespace {

TEST(DemBackend, PileMonitorsFollowThePileVelocityDirection) {
  nlohmann::json config = bed_on_interface();
  config["walls"] = {{{"type", "plane"}, {"point_m", {0, 0, 0}}, {"normal", {0, 0, 1}}}};
  config["pile"] = {{"radius_m", 0.005}, {"tip_z_m", 0.04}, {"length_m", 0.05}, {"velocity_m_s", {0, 0, -0.5}}, {"start_step", 10}};
  DemBackend backend;
  const double dt = backend.configure(config)["dt_suggested"];
  const protocol::AdvanceResult r = backend.advance(request(110, dt, {}));
  // The pile rests for 10 steps, then moves 100 steps at 0.5 m/s: penetration is positive.
  EXPECT_NEAR(r.monitors["pile_displacement_m"].get<double>(), 100 * dt * 0.5, 1e-12);
  EXPECT_TRUE(r.monitors.contains("pile_force_n"));
  EXPECT_TRUE(r.monitors.contains("wall_wall0_force_n"));
  EXPECT_FALSE(r.monitors.contains("interface_force_reaction"));  // uncoupled: no interface monitors
  EXPECT_TRUE(r.outputs.empty());
}

}  // namespace
}  // namespace dfc::dem

namespace dfc::dem {
namespace {

// A pile placed inside the bed region when the bed is generated: no sphere may
// be left inside the closed pile (it would press on the tip from within and
// show up as a negative pile force).
TEST(DemBackend, NoGeneratedSphereIsTrappedInsideThePile) {
  nlohmann::json config = test::box_bed_config();
  config["pile"] = {{"radius_m", 0.012}, {"tip_z_m", 0.004}, {"length_m", 0.05}, {"axis_xy_m", {0.03, 0.03}}};
  DemBackend backend;
  (void)backend.configure(config);
  std::string kind;
  const auto arrays = backend.snapshot(kind);
  const auto position = protocol::find_array(arrays, "particle_position")->to_f64();
  std::size_t below_tip = 0;
  for (std::size_t i = 0; i < position.size() / 3; ++i) {
    const double dx = position[3 * i] - 0.03;
    const double dy = position[3 * i + 1] - 0.03;
    const double z = position[3 * i + 2];
    EXPECT_FALSE(dx * dx + dy * dy < 0.012 * 0.012 && z > 0.004) << "sphere " << i << " is inside the pile";
    if (z < 0.004) ++below_tip;
  }
  EXPECT_GT(position.size() / 3, below_tip) << "spheres outside the pile must remain";
}

}  // namespace
}  // namespace dfc::dem

namespace dfc::dem {
namespace {

// The pile's peak force is the DEM's own monitor (SPEC.md §6.3, 1.5): the
// largest advance-averaged pile_force_n so far, kept by a checkpoint; and
// configure lists the pile's progress monitors for the coupler (§4.2).
TEST(DemBackend, PilePeakForceIsTheLargestAdvanceForceAndSurvivesACheckpoint) {
  nlohmann::json config = bed_on_interface();
  config["walls"] = {{{"type", "plane"}, {"point_m", {0, 0, 0}}, {"normal", {0, 0, 1}}}};
  config["pile"] = {{"radius_m", 0.005}, {"tip_z_m", 0.0245}, {"length_m", 0.05}, {"velocity_m_s", {0, 0, -0.5}}};
  DemBackend backend;
  const nlohmann::json info = backend.configure(config);
  const auto progress = protocol::parse_progress_monitors(info);
  ASSERT_EQ(progress.size(), 3u);
  EXPECT_EQ(progress[0].monitor, "pile_displacement_m");
  EXPECT_EQ(progress[2].monitor, "pile_peak_force_n");
  EXPECT_TRUE(info[protocol::monitor_units_key].contains("pile_peak_force_n"));
  const double dt = info["dt_suggested"];
  double largest = -1e300;
  double last = 0.0;
  for (int k = 0; k < 30; ++k) {
    const protocol::AdvanceResult r = backend.advance(request(100, dt, {}));
    last = r.monitors["pile_force_n"].get<double>();
    largest = std::max(largest, last);
    EXPECT_EQ(r.monitors["pile_peak_force_n"].get<double>(), largest) << "advance " << k;
  }
  ASSERT_GT(largest, 0.0) << "the pile never touched the bed: the test would prove nothing";
  ASSERT_LT(last, largest) << "the force still rises at the end: a restored peak could not be told from the last force";
  const std::string state = backend.checkpoint_state();
  DemBackend resumed;
  (void)resumed.configure(config);
  resumed.restore_state(state);
  EXPECT_EQ(resumed.monitors()["pile_peak_force_n"].get<double>(), largest);
}

}  // namespace
}  // namespace dfc::dem
