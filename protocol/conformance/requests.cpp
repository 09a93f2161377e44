#include "requests.hpp"

#include "check.hpp"
#include "context.hpp"
#include "dfc/common/version.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;

protocol::Message hello_request(std::string version) {
  protocol::Message hello;
  hello.type = protocol::type::hello;
  hello.version = std::move(version);
  hello.body = {{"client", {{"name", "dfc_conformance"}, {"version", std::string(project_version())}}}};
  return hello;
}

protocol::Message advance_request(std::int64_t step, std::int64_t n_steps, double dt) {
  protocol::Message advance;
  advance.type = protocol::type::advance;
  advance.step = step;
  advance.body = {{"n_steps", n_steps}, {"dt", dt}};
  return advance;
}

protocol::Message advance_with_zero_inputs(const Context& context, std::int64_t step, std::int64_t n_steps, double dt,
                                           std::int64_t extra_rows) {
  protocol::Message advance = advance_request(step, n_steps, dt);
  advance.arrays = zero_inputs(context, extra_rows);
  return advance;
}

protocol::Message test_mesh_request() {
  const std::vector<std::int64_t> ids{101, 102, 103, 104};
  const std::vector<double> coordinates{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<std::int64_t> facets{0, 1, 2, 0, 2, 3};
  protocol::Message request;
  request.type = protocol::type::set_interface;
  request.arrays.push_back(protocol::Array::from_i64(protocol::field::node_ids, {kTestMeshNodes}, ids));
  request.arrays.push_back(protocol::Array::from_f64(protocol::field::coordinates, {kTestMeshNodes, 3}, coordinates));
  request.arrays.push_back(protocol::Array::from_i64(protocol::field::facets, {2, 3}, facets));
  return request;
}

bool takes_inputs(const Context& context) { return context.provides_interface || context.accepts_interface; }

std::vector<protocol::Array> zero_inputs(const Context& context, std::int64_t extra_rows) {
  const auto rows_of = [](const std::optional<std::int64_t>& nodes, const char* why) {
    if (!nodes) throw CheckFailure(std::string("not run: ") + why);
    return *nodes;
  };
  std::vector<protocol::Array> inputs;
  if (context.provides_interface) {
    const std::int64_t n = rows_of(context.provided_nodes, "the interface size is unknown (get_interface failed above)") + extra_rows;
    inputs.push_back(protocol::Array::from_f64(protocol::field::force, {n, 3}, std::vector<double>(static_cast<std::size_t>(3 * n), 0.0)));
  }
  if (context.accepts_interface) {
    const std::int64_t n =
        rows_of(context.accepted_nodes, "the server did not accept the test interface mesh, so advance has no velocity input to check") +
        extra_rows;
    inputs.push_back(protocol::Array::from_f64(protocol::field::velocity, {n, 3}, std::vector<double>(static_cast<std::size_t>(3 * n), 0.0)));
  }
  return inputs;
}

}  // namespace dfc::conformance
