// SPEC.md §4.3, §4.1: the interface exchange in the configured state,
// according to the capabilities the server announced.
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
      {"interface.set", "set_interface with a 2-triangle mesh gets ok or a protocol error (accepts_interface), else UNSUPPORTED",
       M::configured, M::none, true, set_interface_matches_capability},
  };
}

}  // namespace dfc::conformance
