// SPEC.md §4.3, §4.1: the interface exchange in the configured state,
// according to the capabilities the server announced.
#include <array>
#include <cmath>
#include <limits>
#include <set>

#include "check.hpp"
#include "context.hpp"
#include "expectations.hpp"
#include "requests.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;

namespace {

void get_interface_matches_capability(Context& context) {
  const protocol::Message reply = context.request(protocol::type::get_interface);
  if (!context.provides_interface) {
    expect_error(reply, {"UNSUPPORTED"});
    return;
  }
  expect_type(reply, protocol::type::interface);
  const auto& ids = expect_array(reply, protocol::field::node_ids, protocol::DType::i64, {-1});
  const std::int64_t n = ids.shape[0];
  expect(n >= 3, "the interface has " + std::to_string(n) + " nodes; a triangle needs at least 3");
  expect_array(reply, protocol::field::coordinates, protocol::DType::f64, {n, 3});
  const auto& facets = expect_array(reply, protocol::field::facets, protocol::DType::i64, {-1, 3});
  expect(facets.shape[0] >= 1, "the interface has no facets");
  for (const auto row : facets.to_i64())
    expect(row >= 0 && row < n, "facets refer to row " + std::to_string(row) + ", outside 0.." + std::to_string(n - 1));
  const auto id_values = ids.to_i64();
  expect(std::set<std::int64_t>(id_values.begin(), id_values.end()).size() == id_values.size(), "node_ids are not unique");
  context.provided_nodes = n;
  context.provided_coordinates = expect_array(reply, protocol::field::coordinates, protocol::DType::f64, {n, 3}).to_f64();
  context.provided_facets = facets.to_i64();
}

using Point = std::array<double, 3>;

Point row_of(const std::vector<double>& values, std::int64_t row) {
  const auto k = static_cast<std::size_t>(3 * row);
  return {values[k], values[k + 1], values[k + 2]};
}

// SPEC.md §4.3: each facet's right-hand normal points out of the continuum.
// Seen from outside, the continuum is where its zones are: the centroid of
// the zone nearest to a facet's centroid must lie behind the facet (against
// its normal). Needs a grid snapshot with zones; zone-less servers cannot be
// checked this way.
void provided_facets_face_out_of_the_continuum(Context& context) {
  if (!context.provides_interface) throw NotApplicable("the server provides no interface");
  if (!context.snapshot) throw NotApplicable("without the snapshot capability the continuum's zones cannot be located");
  if (!context.provided_nodes) throw CheckFailure("not run: get_interface failed above");
  const protocol::Message reply = context.request(protocol::type::snapshot);
  expect_type(reply, protocol::type::snapshot_data);
  const protocol::Array* zones_array = protocol::find_array(reply.arrays, "zone_nodes");
  if (reply.body.value("kind", "") != "grid" || zones_array == nullptr || zones_array->shape.size() != 2 || zones_array->shape[0] == 0)
    throw NotApplicable("the snapshot holds no zones (a zone-less grid, SPEC.md §6.4)");
  const auto nodes = expect_array(reply, "node_position", protocol::DType::f64, {-1, 3}).to_f64();
  const auto zones = zones_array->to_i64();
  const std::int64_t corners = zones_array->shape[1];
  std::vector<Point> centroids;
  for (std::size_t z = 0; z + std::size_t(corners) <= zones.size(); z += std::size_t(corners)) {
    Point c{0, 0, 0};
    for (std::int64_t k = 0; k < corners; ++k) {
      const std::int64_t node = zones[z + std::size_t(k)];
      expect(node >= 0 && std::size_t(node) < nodes.size() / 3, "'zone_nodes' refers to a node outside the snapshot's node_position");
      const Point p = row_of(nodes, node);
      for (int i = 0; i < 3; ++i) c[i] += p[i] / double(corners);
    }
    centroids.push_back(c);
  }
  const auto& xyz = context.provided_coordinates;
  const auto& facets = context.provided_facets;
  std::size_t inward = 0;
  for (std::size_t f = 0; f + 3 <= facets.size(); f += 3) {
    const Point a = row_of(xyz, facets[f]), b = row_of(xyz, facets[f + 1]), c = row_of(xyz, facets[f + 2]);
    const Point u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Point normal{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const Point centre{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
    double nearest = std::numeric_limits<double>::infinity();
    Point behind{};
    for (const Point& z : centroids) {
      const double d = std::hypot(z[0] - centre[0], z[1] - centre[1], z[2] - centre[2]);
      if (d < nearest) {
        nearest = d;
        behind = {z[0] - centre[0], z[1] - centre[1], z[2] - centre[2]};
      }
    }
    if (behind[0] * normal[0] + behind[1] * normal[1] + behind[2] * normal[2] > 0.0) ++inward;
  }
  expect(inward == 0, std::to_string(inward) + " of " + std::to_string(facets.size() / 3) +
                          " interface facets have their right-hand normal pointing into the continuum (towards the nearest zone); "
                          "SPEC.md §4.3 asks for normals out of it");
}

// SPEC.md §4.3 (1.4): node ids are unique; a mesh that repeats one is refused.
void duplicate_node_ids_are_bad_array(Context& context) {
  protocol::Message request = test_mesh_request();
  request.arrays[0] = protocol::Array::from_i64(protocol::field::node_ids, {kTestMeshNodes}, std::vector<std::int64_t>{101, 102, 101, 104});
  const protocol::Message reply = context.request(std::move(request));
  if (context.accepts_interface) expect_error(reply, {"BAD_ARRAY"});
  else expect_error(reply, {"BAD_ARRAY", "UNSUPPORTED"});
}

// Any mesh must be accepted, or refused with a protocol error: never a
// crash or an INTERNAL error. Where it is refused, the advance checks that
// need a velocity input report that they could not run.
void set_interface_matches_capability(Context& context) {
  const protocol::Message reply = context.request(test_mesh_request());
  if (!context.accepts_interface) {
    expect_error(reply, {"UNSUPPORTED"});
    return;
  }
  if (reply.type == protocol::type::ok) {
    context.accepted_nodes = kTestMeshNodes;
    return;
  }
  expect_error(reply, {"BAD_ARRAY", "BAD_CONFIG", "UNSUPPORTED"});
}

}  // namespace

std::vector<Check> interface_checks() {
  using M = Milestone;
  return {
      {"interface.get", "get_interface returns consistent node_ids/coordinates/facets (provides_interface) or UNSUPPORTED",
       M::configured, M::none, true, get_interface_matches_capability},
      {"interface.facets_face_out", "get_interface's facet normals point out of the continuum (away from its nearest zone)",
       M::configured, M::none, true, provided_facets_face_out_of_the_continuum},
      {"interface.duplicate_node_ids", "set_interface whose node_ids repeat an id gets BAD_ARRAY (1.4)", M::configured, M::none, true,
       duplicate_node_ids_are_bad_array, 4},
      {"interface.set", "set_interface with a 2-triangle mesh gets ok or a protocol error (accepts_interface), else UNSUPPORTED",
       M::configured, M::none, true, set_interface_matches_capability},
  };
}

}  // namespace dfc::conformance
