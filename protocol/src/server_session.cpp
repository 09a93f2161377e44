#include "dfc/protocol/server_session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "dfc/common/errors.hpp"
#include "dfc/common/echo.hpp"
#include "dfc/common/json_text.hpp"
#include "dfc/common/state_archive.hpp"
#include "dfc/common/unstable_step_error.hpp"
#include "dfc/common/version.hpp"
#include "dfc/protocol/checkpoint_file.hpp"
#include "dfc/protocol/heartbeat.hpp"

namespace dfc::protocol {

namespace {

/// checkpoint and restore came with 1.3 (SPEC.md §1): a session declaring
/// less answers them as an older server does, UNKNOWN_TYPE.
constexpr int kCheckpointSinceMinor = 3;

std::string allowed_list(std::initializer_list<SessionState> allowed) {
  std::string text;
  for (const auto s : allowed) text += (text.empty() ? "" : " or ") + std::string(session_state_name(s));
  return text;
}

InterfaceMesh interface_from_arrays(const std::vector<Array>& arrays) {
  const Array* ids = find_array(arrays, field::node_ids);
  const Array* facets = find_array(arrays, field::facets);
  if (ids == nullptr || ids->dtype != DType::i64 || ids->shape.size() != 1)
    throw ProtocolError(ErrorCode::bad_array, "set_interface needs array 'node_ids' (i64 [n])");
  if (facets == nullptr || facets->dtype != DType::i64 || facets->shape.size() != 2 || facets->shape[1] != 3)
    throw ProtocolError(ErrorCode::bad_array, "set_interface needs array 'facets' (i64 [m,3])");
  InterfaceMesh mesh;
  mesh.node_ids = ids->to_i64();
  // SPEC.md §4.3: rows are addressed by their ids, so two rows with one id would make the mesh ambiguous.
  std::vector<std::int64_t> sorted = mesh.node_ids;
  std::sort(sorted.begin(), sorted.end());
  if (const auto twin = std::adjacent_find(sorted.begin(), sorted.end()); twin != sorted.end())
    throw ProtocolError(ErrorCode::bad_array, "'node_ids' holds id " + std::to_string(*twin) + " more than once; node ids must be unique");
  mesh.coordinates = require_f64(arrays, field::coordinates, ids->shape[0], 3);
  mesh.facets = facets->to_i64();
  for (const auto index : mesh.facets)
    if (index < 0 || index >= mesh.node_count())
      throw ProtocolError(ErrorCode::bad_array, "'facets' refers to row " + std::to_string(index) + ", outside 0.." +
                                                    std::to_string(mesh.node_count() - 1));
  return mesh;
}
}  // namespace

std::string_view session_state_name(SessionState state) noexcept {
  switch (state) {
    case SessionState::fresh: return "fresh";
    case SessionState::greeted: return "greeted";
    case SessionState::configured: return "configured";
    case SessionState::running: return "running";
    case SessionState::failed: return "failed";
    case SessionState::closed: return "closed";
  }
  return "?";
}

ServerSession::ServerSession(SolverBackend& backend, Limits limits) : backend_(backend), limits_(limits) {}

Message ServerSession::reply_to(const Message& request, std::string_view type) {
  Message reply;
  reply.type = std::string(type);
  reply.seq = next_seq_++;
  reply.reply_to = request.seq;
  reply.version = version_;
  return reply;
}

void ServerSession::require_state(const Message& request, std::initializer_list<SessionState> allowed) const {
  for (const auto s : allowed)
    if (s == state_) return;
  std::string hint;
  if (state_ == SessionState::fresh) hint = "; send hello first";
  else if (state_ == SessionState::greeted) hint = "; send configure first";
  else if (state_ == SessionState::failed) hint = "; the solver failed, only query, snapshot, ping and shutdown are allowed";
  throw ProtocolError(ErrorCode::out_of_order, "'" + echoed(request.type) + "' is allowed when the server is " + allowed_list(allowed) +
                                                   ", but it is " + std::string(session_state_name(state_)) + hint);
}

Message ServerSession::handle(const Message& request) {
  Message reply;
  try {
    const auto version = parse_version(request.version);
    if (!version || version->first != kVersionMajor)
      throw ProtocolError(ErrorCode::version_mismatch, "the client speaks protocol " + request.version + " but this server speaks " +
                                                           version_ + "; major versions must be equal");
    reply = dispatch(request);
  } catch (const ProtocolError& e) {
    reply = make_error(request.seq, e.code(), e.what(), e.key());
  } catch (const ConfigError& e) {
    reply = make_error(request.seq, ErrorCode::bad_config, e.what(), e.key_path());
  } catch (const UnstableStepError& e) {
    // Refused before anything ran: state and step stay, and the client learns the step it may retry with.
    reply = make_error(request.seq, ErrorCode::solver_failure, e.what());
    reply.body["dt_max"] = e.dt_max();
  } catch (const SolverError& e) {
    if (state_ == SessionState::running || state_ == SessionState::configured) state_ = SessionState::failed;
    reply = make_error(request.seq, ErrorCode::solver_failure, e.what());
  } catch (const UserError& e) {
    reply = make_error(request.seq, ErrorCode::bad_config, e.what());
  } catch (const std::exception& e) {
    reply = make_error(request.seq, ErrorCode::internal, std::string("internal error: ") + e.what());
  }
  if (reply.type == type::error) {
    reply.seq = next_seq_++;
    reply.version = version_;
  }
  return reply;
}

Message ServerSession::refuse_undecodable(const DecodeError& error) {
  Message reply = make_error(error.seq(), error.code(), error.what());
  reply.seq = next_seq_++;
  reply.version = version_;
  return reply;
}

Message ServerSession::dispatch(const Message& request) {
  const std::string_view t = request.type;
  if (t == type::hello) return on_hello(request);
  if (t == type::configure) return on_configure(request);
  if (t == type::get_interface) return on_get_interface(request);
  if (t == type::set_interface) return on_set_interface(request);
  if (t == type::advance) return on_advance(request);
  if (t == type::query) return on_query(request);
  if (t == type::snapshot) return on_snapshot(request);
  const bool knows_checkpoints = minor_ >= kCheckpointSinceMinor;  // SPEC.md §1, 1.3
  if (t == type::checkpoint && knows_checkpoints) return on_checkpoint(request);
  if (t == type::restore && knows_checkpoints) return on_restore(request);
  if (t == type::ping) return reply_to(request, type::pong);
  if (t == type::shutdown) {
    state_ = SessionState::closed;
    return reply_to(request, type::bye);
  }
  throw ProtocolError(ErrorCode::unknown_type, "unknown message type '" + echoed(request.type) + "' (protocol " + version_ + ")");
}

Message ServerSession::on_hello(const Message& request) {
  require_state(request, {SessionState::fresh});
  const SolverIdentity id = backend_.identity();
  Message reply = reply_to(request, type::hello_ok);
  reply.body = {{"protocol_version", version_},
                {"solver", {{"name", id.name}, {"version", id.version}}},
                {"role", id.role},
                {"capabilities", id.capabilities},
                {"limits",
                 {{"max_header_bytes", limits_.max_header_bytes},
                  {"max_array_bytes", limits_.max_array_bytes},
                  {"max_arrays", limits_.max_arrays}}}};
  if (!heartbeat_endpoint_.empty()) reply.body[heartbeat::endpoint_key] = heartbeat_endpoint_;
  state_ = SessionState::greeted;
  return reply;
}

Message ServerSession::on_configure(const Message& request) {
  require_state(request, {SessionState::greeted});
  const auto text = request.body.find("section_json");
  if (text == request.body.end() || !text->is_string())
    throw ProtocolError(ErrorCode::bad_message, "configure needs body.section_json: the scenario section as JSON text");
  const std::string& section_text = text->get_ref<const std::string&>();
  nlohmann::json section;
  try {
    section = parse_json_text(section_text, JsonTextLimits{.reject_duplicate_keys = true});
  } catch (const JsonTextError& e) {
    if (e.kind() == JsonTextError::Kind::syntax)
      throw ProtocolError(ErrorCode::bad_config, "body.section_json is not valid JSON: " + std::string(e.what()));
    throw ConfigError(e.key_path(), e.reason());
  }
  if (!section.is_object()) throw ProtocolError(ErrorCode::bad_config, "body.section_json is not a JSON object");
  nlohmann::json info = backend_.configure(section);
  Message reply = reply_to(request, type::configured);
  section_hash_ = fnv1a64_hex(section_text);
  reply.body = {{"scenario_hash", section_hash_}, {"info", std::move(info)}};
  state_ = SessionState::configured;
  return reply;
}

Message ServerSession::on_get_interface(const Message& request) {
  require_state(request, {SessionState::configured});
  const InterfaceMesh mesh = backend_.interface_mesh();
  Message reply = reply_to(request, type::interface);
  const std::int64_t n = mesh.node_count();
  reply.arrays.push_back(Array::from_i64(field::node_ids, {n}, mesh.node_ids));
  reply.arrays.push_back(Array::from_f64(field::coordinates, {n, 3}, mesh.coordinates));
  reply.arrays.push_back(Array::from_i64(field::facets, {mesh.facet_count(), 3}, mesh.facets));
  return reply;
}

Message ServerSession::on_set_interface(const Message& request) {
  require_state(request, {SessionState::configured});
  const InterfaceMesh mesh = interface_from_arrays(request.arrays);
  backend_.set_interface(mesh);
  return reply_to(request, type::ok);
}

Message ServerSession::on_advance(const Message& request) {
  require_state(request, {SessionState::configured, SessionState::running});
  if (!request.step)
    throw ProtocolError(ErrorCode::bad_message, "advance needs header field 'step' (the server's current step, " + std::to_string(step_) + ")");
  if (*request.step != step_)
    throw ProtocolError(ErrorCode::step_mismatch, "advance.step is " + std::to_string(*request.step) + " but the server is at step " +
                                                      std::to_string(step_));
  const auto n = request.body.find("n_steps");
  const auto dt = request.body.find("dt");
  if (n == request.body.end() || !n->is_number_integer() || n->get<std::int64_t>() < 1 || n->get<std::int64_t>() > kMaxStepsPerAdvance)
    throw ProtocolError(ErrorCode::bad_message, "advance needs body.n_steps, an integer in 1.." + std::to_string(kMaxStepsPerAdvance));
  if (dt == request.body.end() || !dt->is_number() || !(dt->get<double>() > 0.0) || !std::isfinite(dt->get<double>()))
    throw ProtocolError(ErrorCode::bad_message, "advance needs body.dt, a positive finite number of seconds");
  AdvanceRequest advance{step_, n->get<std::int64_t>(), dt->get<double>(), request.arrays};
  const auto solver_start = std::chrono::steady_clock::now();
  AdvanceResult result = backend_.advance(advance);
  const double solver_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - solver_start).count();
  advance_statistics_.solver_seconds += solver_seconds;
  if (advance_statistics_.advances == 0) advance_statistics_.first_advance_seconds = solver_seconds;
  advance_statistics_.advances += 1;
  advance_statistics_.steps += advance.n_steps;
  step_ += advance.n_steps;
  state_ = SessionState::running;
  Message reply = reply_to(request, type::advanced);
  reply.step = step_;
  reply.body = {{"monitors", std::move(result.monitors)}};
  reply.arrays = std::move(result.outputs);
  return reply;
}

Message ServerSession::on_query(const Message& request) {
  require_state(request, {SessionState::configured, SessionState::running, SessionState::failed});
  Message reply = reply_to(request, type::monitors);
  reply.step = step_;
  reply.body = {{"monitors", backend_.monitors()}};
  return reply;
}

Message ServerSession::on_snapshot(const Message& request) {
  require_state(request, {SessionState::configured, SessionState::running, SessionState::failed});
  std::string kind;
  Message reply = reply_to(request, type::snapshot_data);
  reply.arrays = backend_.snapshot(kind);
  reply.step = step_;
  reply.body = {{"kind", kind}};
  return reply;
}

std::string ServerSession::checkpoint_path(const Message& request) const {
  const auto& capabilities = backend_.identity().capabilities;
  if (std::find(capabilities.begin(), capabilities.end(), capability::checkpoint) == capabilities.end())
    throw ProtocolError(ErrorCode::unsupported, "'" + echoed(request.type) + "' needs capability 'checkpoint', which this server lacks");
  const auto path = request.body.find("path");
  if (path == request.body.end() || !path->is_string() || path->get_ref<const std::string&>().empty())
    throw ProtocolError(ErrorCode::bad_message, "'" + echoed(request.type) + "' needs body.path: the checkpoint file's path, a non-empty string");
  return path->get<std::string>();
}

Message ServerSession::on_checkpoint(const Message& request) {
  require_state(request, {SessionState::configured, SessionState::running});
  const std::string path = checkpoint_path(request);
  const SolverIdentity id = backend_.identity();
  const std::string state = backend_.checkpoint_state();
  write_checkpoint_file(path, {id.name, id.version, section_hash_, step_}, state);
  Message reply = reply_to(request, type::checkpointed);
  reply.step = step_;
  reply.body = {{"path", path}, {"state_bytes", state.size()}};
  return reply;
}

Message ServerSession::on_restore(const Message& request) {
  // Only before the first advance: the section (and interface) the state belongs to are set, nothing has run.
  require_state(request, {SessionState::configured});
  const std::string path = checkpoint_path(request);
  const SolverIdentity id = backend_.identity();
  const CheckpointFile file = read_checkpoint_file(path);
  if (const std::string why = checkpoint_mismatch(file.header, {id.name, id.version, section_hash_, step_}); !why.empty())
    throw ProtocolError(ErrorCode::bad_checkpoint, "checkpoint file '" + path + "' cannot be restored: " + why);
  try {
    backend_.restore_state(file.state);
  } catch (const StateFormatError& e) {
    // The backend may have replaced part of its state: nothing but a fresh server can be trusted now.
    state_ = SessionState::failed;
    throw ProtocolError(ErrorCode::bad_checkpoint, std::string(e.what()) + "; the server's state is now undefined: restart it");
  } catch (const ProtocolError& e) {
    state_ = SessionState::failed;
    throw ProtocolError(e.code(), std::string(e.what()) + "; the server's state is now undefined: restart it", e.key());
  }
  step_ = file.header.step;
  state_ = SessionState::running;
  Message reply = reply_to(request, type::restored);
  reply.step = step_;
  return reply;
}

}  // namespace dfc::protocol
