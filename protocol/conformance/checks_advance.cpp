// SPEC.md §5.2, §6: step semantics, refused advances leaving the step
// unchanged, interface outputs, then query, snapshot and the ordering rules
// of the running state.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "check.hpp"
#include "context.hpp"
#include "dfc/protocol/monitor_units.hpp"
#include "dfc/protocol/progress_monitors.hpp"
#include "expectations.hpp"
#include "requests.hpp"

namespace dfc::conformance {

namespace protocol = dfc::protocol;

namespace {

/// A refused advance must not have moved the server's step (SPEC.md §5.2).
void expect_step_unchanged(Context& context) {
  const protocol::Message reply = context.request(protocol::type::query);
  expect_type(reply, protocol::type::monitors);
  expect(reply.step.has_value() && *reply.step == context.step,
         "after the refused advance, query reports step " + (reply.step ? std::to_string(*reply.step) : "(none)") + " instead of " +
             std::to_string(context.step));
}

protocol::Message advance_with_inputs(Context& context, std::int64_t step, std::int64_t n_steps, double dt, std::int64_t extra_rows = 0) {
  return context.request(advance_with_zero_inputs(context, step, n_steps, dt, extra_rows));
}

void wrong_step_is_step_mismatch(Context& context) {
  expect_error(advance_with_inputs(context, context.step + 7, 1, context.dt), {"STEP_MISMATCH"});
  expect_step_unchanged(context);
}

void zero_steps_is_bad_message(Context& context) {
  expect_error(advance_with_inputs(context, context.step, 0, context.dt), {"BAD_MESSAGE"});
  expect_step_unchanged(context);
}

void negative_dt_is_bad_message(Context& context) {
  expect_error(advance_with_inputs(context, context.step, 1, -context.dt), {"BAD_MESSAGE"});
  expect_step_unchanged(context);
}

void missing_input_is_bad_array(Context& context) {
  if (!takes_inputs(context)) throw NotApplicable("the server announces no interface capability, so advance takes no inputs");
  (void)zero_inputs(context);  // only meaningful once the interface exists; says "not run" otherwise
  expect_error(context.request(advance_request(context.step, 1, context.dt)), {"BAD_ARRAY"});
  expect_step_unchanged(context);
}

void misshapen_input_is_bad_array(Context& context) {
  if (!takes_inputs(context)) throw NotApplicable("the server announces no interface capability, so advance takes no inputs");
  const protocol::Message reply = advance_with_inputs(context, context.step, 1, context.dt, 1);
  expect_error(reply, {"BAD_ARRAY"});
  const std::string message = reply.body["message"].get<std::string>();
  const char* name = context.provides_interface ? protocol::field::force : protocol::field::velocity;
  expect(message.find(name) != std::string::npos, "the BAD_ARRAY message does not name the array '" + std::string(name) + "': \"" + message + "\"");
  expect_step_unchanged(context);
}

// SPEC.md §6.1 (1.1): an input array the server does not take is refused, named.
void unexpected_input_is_bad_array(Context& context) {
  const std::string surplus = "conformance_surplus";
  protocol::Message request = advance_request(context.step, 1, context.dt);
  request.arrays = takes_inputs(context) ? zero_inputs(context) : std::vector<protocol::Array>{};
  request.arrays.push_back(protocol::Array::from_f64(surplus, {1}, std::vector<double>{0.0}));
  const protocol::Message reply = context.request(std::move(request));
  expect_error(reply, {"BAD_ARRAY"});
  const std::string message = reply.body["message"].get<std::string>();
  expect(message.find(surplus) != std::string::npos, "the BAD_ARRAY message does not name the array '" + surplus + "': \"" + message + "\"");
  expect_step_unchanged(context);
}

// SPEC.md §5.2 (1.4): a dt above the announced dt_max is refused before
// anything runs, with the largest stable step as a number, and the server
// stays usable: a wrong-step advance then gets STEP_MISMATCH, not the
// OUT_OF_ORDER of a failed server.
void unstable_dt_is_refused_with_dt_max(Context& context) {
  if (!context.dt_max) throw NotApplicable("configured.info.dt_max is null: every step is stable");
  const protocol::Message reply = advance_with_inputs(context, context.step, 1, 10.0 * *context.dt_max);
  expect_error(reply, {"SOLVER_FAILURE"});
  expect(reply.body.contains("dt_max") && reply.body["dt_max"].is_number() && reply.body["dt_max"].get<double>() > 0.0,
         "the SOLVER_FAILURE for dt = 10 dt_max lacks a positive number body.dt_max: " + reply.body.dump());
  expect(reply.body["dt_max"].get<double>() < 10.0 * *context.dt_max, "body.dt_max " + reply.body["dt_max"].dump() +
                                                                          " s is not below the refused dt");
  expect_step_unchanged(context);
  const protocol::Message probe = advance_with_inputs(context, context.step + 7, 1, context.dt);
  expect(probe.type == protocol::type::error && probe.body.value("code", "") == "STEP_MISMATCH",
         "after refusing the unstable dt the server answers a wrong-step advance with " + probe.body.value("code", probe.type) +
             ", not STEP_MISMATCH: it must keep its state (SPEC.md §5.2)");
}

// SPEC.md §6.1, §6.3: with NON-ZERO interface forces a provider reports their
// sum as interface_force_received, and interface_power_w as Σ f·v with the
// velocity averaged over the advance, which for one step is the velocity it
// returns. Both are sums of the same terms in some order: a relative
// tolerance of 1e-9 leaves room for the order, not for a wrong term.
void provider_reports_the_forces_it_received(Context& context) {
  if (!context.provides_interface) throw NotApplicable("the server provides no interface");
  if (!context.provided_nodes) throw CheckFailure("not run: get_interface failed above");
  const std::int64_t n = *context.provided_nodes;
  std::vector<double> force(static_cast<std::size_t>(3 * n));
  std::array<double, 3> sum{0, 0, 0};
  for (std::size_t k = 0; k < force.size(); ++k) {
    force[k] = 1e-3 * (double(k % 7) - 3.0) + 2e-4;  // small, mixed signs, no two rows alike in sum
    sum[k % 3] += force[k];
  }
  protocol::Message request = advance_request(context.step, 1, context.dt);
  request.arrays = zero_inputs(context);
  for (auto& array : request.arrays)
    if (array.name == protocol::field::force) array = protocol::Array::from_f64(protocol::field::force, {n, 3}, force);
  const protocol::Message reply = context.request(std::move(request));
  expect_type(reply, protocol::type::advanced);
  context.step += 1;
  const nlohmann::json& monitors = reply.body.value("monitors", nlohmann::json::object());
  const nlohmann::json received = monitors.value("interface_force_received", nlohmann::json());
  expect(received.is_array() && received.size() == 3, "monitor interface_force_received is not an [x, y, z] array: " + received.dump());
  double scale = 0.0;
  for (const double f : force) scale += std::abs(f);
  for (std::size_t i = 0; i < 3; ++i)
    expect(received[i].is_number() && std::abs(received[i].get<double>() - sum[i]) <= 1e-9 * scale,
           "interface_force_received " + received.dump() + " is not the sum of the forces sent [" + std::to_string(sum[0]) + ", " +
               std::to_string(sum[1]) + ", " + std::to_string(sum[2]) + "]");
  const auto velocity = expect_array(reply, protocol::field::velocity, protocol::DType::f64, {n, 3}).to_f64();
  double power = 0.0, power_scale = 0.0;
  for (std::size_t k = 0; k < force.size(); ++k) {
    power += force[k] * velocity[k];
    power_scale += std::abs(force[k] * velocity[k]);
  }
  if (!monitors.contains("interface_power_w")) return;  // optional (SPEC.md §6.3); when sent, it must be right
  const nlohmann::json& reported = monitors["interface_power_w"];
  expect(reported.is_number(), "monitor interface_power_w is not a number: " + reported.dump());
  expect(std::abs(reported.get<double>() - power) <= 1e-9 * power_scale + 1e-300,
         "interface_power_w " + reported.dump() + " W is not Σ force · velocity = " + std::to_string(power) +
             " W over the forces sent and the velocities returned (one step: the velocity averaged over the advance)");
}

/// The advanced reply's outputs per SPEC.md §6.1 and its monitors.
void expect_outputs(const Context& context, const protocol::Message& reply) {
  if (context.provides_interface) {
    const std::int64_t n = *context.provided_nodes;
    expect_array(reply, protocol::field::velocity, protocol::DType::f64, {n, 3});
    expect_array(reply, protocol::field::displacement, protocol::DType::f64, {n, 3});
  }
  if (context.accepts_interface) {
    const std::int64_t n = *context.accepted_nodes;
    expect_array(reply, protocol::field::force, protocol::DType::f64, {n, 3});
    if (protocol::find_array(reply.arrays, protocol::field::mass) != nullptr) expect_array(reply, protocol::field::mass, protocol::DType::f64, {n});
  }
  expect(reply.body.contains("monitors"), "'advanced' lacks body.monitors");
  expect_monitors(reply.body["monitors"], "advanced");
}

void advance_by(Context& context, std::int64_t n_steps) {
  const protocol::Message reply = advance_with_inputs(context, context.step, n_steps, context.dt);
  expect_type(reply, protocol::type::advanced);
  expect_step(reply, context.step + n_steps);
  context.step += n_steps;
  expect_outputs(context, reply);
}

void one_step(Context& context) { advance_by(context, 1); }
void two_steps(Context& context) { advance_by(context, 2); }

void query_reports_step_and_monitors(Context& context) {
  const protocol::Message reply = context.request(protocol::type::query);
  expect_type(reply, protocol::type::monitors);
  expect_step(reply, context.step);
  expect(reply.body.contains("monitors"), "'monitors' lacks body.monitors");
  expect_monitors(reply.body["monitors"], "monitors");
}

// SPEC.md §6.3 (1.2): configure's info.monitor_units gives a unit to every
// monitor the server sends, so that no results column is left to a guess.
void declared_units_cover_monitors(Context& context) {
  const protocol::Message reply = context.request(protocol::type::query);
  expect_type(reply, protocol::type::monitors);
  const std::vector<std::string> missing = protocol::undeclared_monitors(reply.body.value("monitors", nlohmann::json::object()), context.monitor_units);
  std::string names;
  for (const std::string& name : missing) names += (names.empty() ? "'" : ", '") + name + "'";
  expect(missing.empty(), "configured.info.monitor_units gives no unit string for the monitor(s) " + names);
}

// SPEC.md §4.2 (1.5): info.progress_monitors, when present, is well formed and
// names number monitors that are declared and sent after a step.
void progress_monitors_are_declared_and_sent(Context& context) {
  std::vector<protocol::ProgressMonitor> entries;
  try {
    entries = protocol::parse_progress_monitors(context.configured_info);
  } catch (const std::invalid_argument& e) {
    expect(false, std::string("configured.") + e.what());
  }
  if (entries.empty()) throw NotApplicable("configured.info lists no progress_monitors (optional)");
  const protocol::Message reply = context.request(protocol::type::query);
  expect_type(reply, protocol::type::monitors);
  const nlohmann::json monitors = reply.body.value("monitors", nlohmann::json::object());
  for (const protocol::ProgressMonitor& entry : entries) {
    expect(context.monitor_units.is_null() || (context.monitor_units.contains(entry.monitor) && context.monitor_units[entry.monitor].is_string()),
           "progress monitor '" + entry.monitor + "' has no unit in configured.info.monitor_units");
    const auto value = monitors.find(entry.monitor);
    expect(value != monitors.end() && (value->is_number() || value->is_null()),
           "progress monitor '" + entry.monitor + "' is not a number monitor of the query after a step" +
               (value == monitors.end() ? std::string(" (missing)") : ", got " + value->dump().substr(0, 80)));
  }
}

void expect_index_rows(const protocol::Array& indices, std::int64_t rows) {
  const auto values = indices.to_i64();
  expect(std::all_of(values.begin(), values.end(), [rows](std::int64_t v) { return v >= 0 && v < rows; }),
         "'" + indices.name + "' refers to a row outside 0.." + std::to_string(rows - 1));
}

void snapshot_matches_capability(Context& context) {
  const protocol::Message reply = context.request(protocol::type::snapshot);
  if (!context.snapshot) {
    expect_error(reply, {"UNSUPPORTED"});
    return;
  }
  expect_type(reply, protocol::type::snapshot_data);
  expect_step(reply, context.step);
  const std::string kind = reply.body.value("kind", "");
  using protocol::DType;
  if (kind == "particles") {
    const std::int64_t n = expect_array(reply, "particle_position", DType::f64, {-1, 3}).shape[0];
    expect_array(reply, "particle_radius", DType::f64, {n});
    expect_array(reply, "particle_velocity", DType::f64, {n, 3});
    expect_array(reply, "particle_id", DType::i64, {n});
    if (protocol::find_array(reply.arrays, "wall_facets") != nullptr) {
      const std::int64_t k = expect_array(reply, "wall_vertices", DType::f64, {-1, 3}).shape[0];
      expect_index_rows(expect_array(reply, "wall_facets", DType::i64, {-1, 3}), k);
    }
  } else if (kind == "grid") {
    const std::int64_t n = expect_array(reply, "node_position", DType::f64, {-1, 3}).shape[0];
    expect_array(reply, "node_displacement", DType::f64, {n, 3});
    expect_array(reply, "node_velocity", DType::f64, {n, 3});
    // A grid without zones may omit both zone arrays (SPEC.md §6.4).
    if (protocol::find_array(reply.arrays, "zone_nodes") != nullptr || protocol::find_array(reply.arrays, "zone_stress") != nullptr) {
      const std::int64_t m = expect_array(reply, "zone_nodes", DType::i64, {-1, 8}).shape[0];
      expect_index_rows(*protocol::find_array(reply.arrays, "zone_nodes"), n);
      expect_array(reply, "zone_stress", DType::f64, {m, 6});
    }
  } else {
    throw CheckFailure("snapshot_data.kind is '" + kind + "', expected 'particles' or 'grid'");
  }
}

void get_interface_when_running_is_out_of_order(Context& context) {
  const protocol::Message reply = context.request(protocol::type::get_interface);
  if (context.provides_interface) expect_error(reply, {"OUT_OF_ORDER"});
  else expect_error(reply, {"OUT_OF_ORDER", "UNSUPPORTED"});
}

void set_interface_when_running_is_out_of_order(Context& context) {
  const protocol::Message reply = context.request(test_mesh_request());
  if (context.accepts_interface) expect_error(reply, {"OUT_OF_ORDER"});
  else expect_error(reply, {"OUT_OF_ORDER", "UNSUPPORTED"});
}

}  // namespace

std::vector<Check> advance_checks() {
  using M = Milestone;
  return {
      {"advance.step_mismatch", "advance from the wrong step gets STEP_MISMATCH and the step is unchanged", M::configured, M::none, true,
       wrong_step_is_step_mismatch},
      {"advance.zero_steps", "advance with n_steps 0 gets BAD_MESSAGE", M::configured, M::none, true, zero_steps_is_bad_message},
      {"advance.negative_dt", "advance with dt < 0 gets BAD_MESSAGE", M::configured, M::none, true, negative_dt_is_bad_message},
      {"advance.missing_input", "advance without its interface input gets BAD_ARRAY", M::configured, M::none, true,
       missing_input_is_bad_array},
      {"advance.unexpected_input", "an input array the server does not take gets BAD_ARRAY naming it (1.1)", M::configured, M::none, true,
       unexpected_input_is_bad_array, 1},
      {"advance.wrong_input_shape", "an input with n+1 rows gets BAD_ARRAY naming the array", M::configured, M::none, true,
       misshapen_input_is_bad_array},
      {"advance.unstable_dt", "advance with dt = 10 dt_max gets SOLVER_FAILURE with body.dt_max and changes nothing (1.4)", M::configured,
       M::none, true, unstable_dt_is_refused_with_dt_max, 4},
      {"advance.one_step", "advance 1 step from 0 gets advanced at step 1 with outputs of SPEC §6.1", M::configured, M::stepped, true,
       one_step},
      {"advance.two_steps", "advance 2 steps from 1 gets advanced at step 3", M::stepped, M::none, true, two_steps},
      {"advance.forces_received", "a provider's interface_force_received and interface_power_w match non-zero forces sent", M::stepped,
       M::none, true, provider_reports_the_forces_it_received},
      {"running.query", "query gets monitors at the current step", M::configured, M::none, true, query_reports_step_and_monitors},
      {"running.monitor_units", "configure's info.monitor_units gives the unit of every monitor sent after a step (1.2)", M::stepped,
       M::none, true, declared_units_cover_monitors, 2},
      {"running.progress_monitors", "configure's info.progress_monitors, if any, is well formed and names number monitors sent (1.5)",
       M::stepped, M::none, true, progress_monitors_are_declared_and_sent, 5},
      {"running.snapshot", "snapshot gets snapshot_data with a kind and its arrays (snapshot capability), else UNSUPPORTED",
       M::configured, M::none, true, snapshot_matches_capability},
      {"running.get_interface_refused", "get_interface after advancing gets OUT_OF_ORDER", M::stepped, M::none, true,
       get_interface_when_running_is_out_of_order},
      {"running.set_interface_refused", "set_interface after advancing gets OUT_OF_ORDER", M::stepped, M::none, true,
       set_interface_when_running_is_out_of_order},
  };
}

}  // namespace dfc::conformance
