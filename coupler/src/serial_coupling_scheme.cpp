#include "dfc/coupler/serial_coupling_scheme.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "dfc/common/errors.hpp"

namespace dfc::coupler {

namespace {

constexpr double kNaN = ExchangeResult::kUnknown;

/// The [x, y, z] monitor `name`, or nullopt when the server did not send it.
/// Entries that are not numbers read as NaN, so the balance check catches them.
std::optional<std::array<double, 3>> vector_monitor(const nlohmann::json& monitors, const char* name) {
  const auto it = monitors.find(name);
  if (it == monitors.end() || !it->is_array() || it->size() != 3) return std::nullopt;
  const auto component = [&](std::size_t i) { return (*it)[i].is_number() ? (*it)[i].get<double>() : kNaN; };
  return std::array<double, 3>{component(0), component(1), component(2)};
}

bool all_finite(const std::array<double, 3>& v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

/// Throws naming the first node row of interface array `name` that holds a NaN
/// or an infinity; the caller blames the server that sent it.
void require_finite_rows(const std::vector<double>& values, const char* name) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw SolverError("it sent a non-finite interface " + std::string(name) + " (" + std::to_string(values[i]) + " in node row " +
                        std::to_string(i / 3) + ")");
}

std::string format_vector(const std::array<double, 3>& v) {
  std::ostringstream out;
  out.precision(6);
  out << "[" << v[0] << ", " << v[1] << ", " << v[2] << "]";
  return out.str();
}

/// Largest component-wise |a + b| relative to the largest component (NaN when either holds a non-finite value).
double relative_mismatch(const std::array<double, 3>& on_dem, const std::array<double, 3>& on_continuum) {
  double mismatch = 0.0;
  double scale = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    mismatch = std::max(mismatch, std::abs(on_dem[i] + on_continuum[i]));
    scale = std::max({scale, std::abs(on_dem[i]), std::abs(on_continuum[i])});
  }
  // std::max drops NaN, so non-finite forces are tested for on their own.
  return !all_finite(on_dem) || !all_finite(on_continuum) ? kNaN : scale > 0 ? mismatch / scale : mismatch;
}

}  // namespace

SerialCouplingScheme::SerialCouplingScheme(Participant* dem, Participant* continuum, const ExchangeTiming& timing,
                                           std::int64_t interface_nodes, double force_balance_tolerance, std::chrono::milliseconds deadline,
                                           StopRequest& stop)
    : dem_(dem),
      continuum_(continuum),
      timing_(timing),
      nodes_(interface_nodes),
      tolerance_(force_balance_tolerance),
      deadline_(deadline),
      stop_(stop) {
  state_.velocity.assign(std::size_t(nodes_) * 3, 0.0);
  state_.continuum_displacement.assign(state_.velocity.size(), 0.0);
  state_.wall_displacement.assign(state_.velocity.size(), 0.0);
}

double SerialCouplingScheme::time() const {
  return dem_ != nullptr ? double(state_.dem_step) * timing_.dt_dem : double(state_.continuum_step) * timing_.dt_continuum;
}

ExchangeResult SerialCouplingScheme::advance() {
  ExchangeResult result;
  result.exchange = state_.exchanges_done;
  std::vector<protocol::Array> to_continuum;
  if (dem_ != nullptr) advance_dem(result, to_continuum);
  if (continuum_ != nullptr) advance_continuum(result, std::move(to_continuum));
  if (coupled()) check_force_balance(result);
  result.dem_step = state_.dem_step;
  result.continuum_step = state_.continuum_step;
  result.time_s = time();
  ++state_.exchanges_done;
  return result;
}

// Interface kinematics. The continuum returns its gridpoint velocity and
// displacement at the end of each advance; the DEM moves its wall vertices at
// the velocity it is sent for the whole exchange. Sending the bare
// end-of-advance velocity would let the wall drift from the gridpoints
// whenever k or m > 1 (the continuum's velocity varies inside its advance), so
// the coupler tracks where it has moved the wall (x += v·dt, step by step, as
// the DEM does) and adds the correction that brings the wall onto the
// continuum's displacement: v_sent = v + (u_continuum − u_wall) / T.
std::vector<double> SerialCouplingScheme::corrected_wall_velocity() {
  const double exchange_time = timing_.exchange_duration();
  const std::vector<double>& velocity = state_.velocity;
  std::vector<double>& wall_displacement = state_.wall_displacement;
  std::vector<double> sent(velocity.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    stop_.check("the coupler's update of the wall positions");  // k can be 1e9 steps per node
    sent[i] = velocity[i] + (state_.continuum_displacement[i] - wall_displacement[i]) / exchange_time;
    for (std::int64_t s = 0; s < timing_.dem_steps_per_exchange; ++s) wall_displacement[i] += sent[i] * timing_.dt_dem;
  }
  return sent;
}

void SerialCouplingScheme::advance_dem(ExchangeResult& result, std::vector<protocol::Array>& to_continuum) {
  std::vector<protocol::Array> inputs;
  if (coupled()) inputs.push_back(protocol::Array::from_f64(protocol::field::velocity, {nodes_, 3}, corrected_wall_velocity()));
  protocol::Message reply;
  try {
    reply = dem_->client().advance(state_.dem_step, timing_.dem_steps_per_exchange, timing_.dt_dem, std::move(inputs), deadline_);
    if (coupled()) {
      const std::vector<double> force = protocol::require_f64(reply.arrays, protocol::field::force, nodes_, 3);
      require_finite_rows(force, "force");
      to_continuum.push_back(protocol::Array::from_f64(protocol::field::force, {nodes_, 3}, force));
      // A driven continuum also lends its interface mass (SPEC.md §6.1).
      if (protocol::find_array(reply.arrays, protocol::field::mass) != nullptr)
        to_continuum.push_back(
            protocol::Array::from_f64(protocol::field::mass, {nodes_}, protocol::require_f64(reply.arrays, protocol::field::mass, nodes_, 0)));
    }
  } catch (const std::exception& e) {
    dem_->fail(e, "advancing from step " + std::to_string(state_.dem_step));
  }
  state_.dem_step = *reply.step;
  result.monitors["dem"] = reply.body.value("monitors", nlohmann::json::object());
}

void SerialCouplingScheme::advance_continuum(ExchangeResult& result, std::vector<protocol::Array> from_dem) {
  protocol::Message reply;
  try {
    reply = continuum_->client().advance(state_.continuum_step, timing_.continuum_steps_per_exchange, timing_.dt_continuum,
                                         std::move(from_dem), deadline_);
    if (coupled()) {
      state_.velocity = protocol::require_f64(reply.arrays, protocol::field::velocity, nodes_, 3);
      state_.continuum_displacement = protocol::require_f64(reply.arrays, protocol::field::displacement, nodes_, 3);
      // Caught here, a NaN is blamed on the continuum that produced it, not on the DEM it would break next.
      require_finite_rows(state_.velocity, "velocity");
      require_finite_rows(state_.continuum_displacement, "displacement");
    }
  } catch (const std::exception& e) {
    continuum_->fail(e, "advancing from step " + std::to_string(state_.continuum_step));
  }
  state_.continuum_step = *reply.step;
  result.monitors["continuum"] = reply.body.value("monitors", nlohmann::json::object());
}

// The interface forces must be equal and opposite (docs/theory/coupling.md §4):
// the reaction the DEM computed on its particles against what the continuum applied.
void SerialCouplingScheme::check_force_balance(ExchangeResult& result) {
  const auto reaction = vector_monitor(result.monitors["dem"], "interface_force_reaction");
  const auto received = vector_monitor(result.monitors["continuum"], "interface_force_received");
  if (reaction) result.force_on_dem = *reaction;
  if (received) result.force_on_continuum = *received;
  if (!reaction || !received) {
    ++state_.unchecked_balances;
    if (state_.missing_balance_monitors.empty())
      state_.missing_balance_monitors =
          !reaction ? "the dem server sent no interface_force_reaction" : "the continuum server sent no interface_force_received";
    return;
  }
  const double relative = relative_mismatch(result.force_on_dem, result.force_on_continuum);
  if (!std::isfinite(relative) || relative > tolerance_) {
    std::ostringstream message;
    message << "interface force balance broken at exchange " << result.exchange << " (DEM step " << state_.dem_step
            << "): force on the DEM side " << format_vector(result.force_on_dem) << " N (interface_force_reaction) and on the continuum "
            << format_vector(result.force_on_continuum) << " N (interface_force_received) are not equal and opposite; relative mismatch "
            << relative << " > tolerance " << tolerance_ << " (coupling.force_balance_tolerance)";
    throw ParticipantFailure(message.str());
  }
  state_.worst_balance = std::max(state_.worst_balance, relative);
}

}  // namespace dfc::coupler
