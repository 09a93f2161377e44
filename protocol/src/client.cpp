#include "dfc/protocol/client.hpp"

#include "dfc/common/durations.hpp"
#include "dfc/common/echo.hpp"
#include "dfc/common/version.hpp"
#include "dfc/protocol/authentication.hpp"
#include "dfc/protocol/heartbeat.hpp"
#include "dfc/protocol/transport.hpp"

namespace dfc::protocol {

namespace {
constexpr auto kSlice = std::chrono::milliseconds(100);
// A gap this long between two slices of a wait is a pause of this process
// itself, not time the server had (see await_reply).
constexpr auto kPause = std::chrono::seconds(1);

std::string shape_mismatch(const std::string& label, const std::string& what) { return label + " sent " + what; }
}  // namespace

Connection::Connection(zmq::context_t& context, const std::string& endpoint, std::string label, Limits limits,
                       std::optional<std::string> server_key)
    : socket_(context, zmq::socket_type::dealer), endpoint_(endpoint), server_key_(std::move(server_key)), label_(std::move(label)), limits_(limits) {
  configure_socket(socket_, limits_);
  authentication::secure_client_socket(socket_, server_key_);
  socket_.connect(endpoint);
}

void Connection::watch_heartbeat(zmq::context_t& context, const std::string& endpoint, HangTimeouts timeouts) {
  if (const auto problem = endpoint_problem(endpoint))
    throw RemoteError("BAD_MESSAGE", label_ + " announced a heartbeat_endpoint that is no endpoint: " + *problem + " (SPEC.md §9.1)", "");
  heartbeat_.emplace(context, heartbeat::connect_endpoint(endpoint, endpoint_), timeouts, server_key_);
}

std::optional<Message> Connection::await_reply(std::optional<std::int64_t> seq, std::chrono::milliseconds deadline) {
  auto until = std::chrono::steady_clock::now() + deadline;
  auto last_slice = std::chrono::steady_clock::now();
  skipped_reply_to_.clear();
  if (heartbeat_) heartbeat_->begin_wait();
  while (true) {
    if (wait_hook_) wait_hook_();
    if (heartbeat_) {
      const Liveliness liveliness = heartbeat_->poll();
      if (liveliness == Liveliness::silent) throw HungError(label_, HungError::Kind::silent, "no reply, and " + heartbeat_->silence_description());
      if (liveliness == Liveliness::stalled) throw HungError(label_, HungError::Kind::stalled, "no reply, and " + heartbeat_->stall_description());
    }
    // The whole job stopped and continued (a batch system's suspend, SIGSTOP
    // and SIGCONT; a suspended virtual machine): the time this process did not
    // run is no time the server had to answer, so the deadline moves by it, as
    // the heartbeat's silence rule does not count it either. Measured between
    // two deadline checks, so a pause anywhere in the slice is seen.
    const auto now = std::chrono::steady_clock::now();
    if (now - last_slice > kPause) until += now - last_slice - kSlice;
    last_slice = now;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - now);
    if (left.count() <= 0) return std::nullopt;
    auto frames = receive_frames(socket_, std::min(left, std::chrono::milliseconds(kSlice)));
    if (!frames) continue;
    const auto views = frame_views(*frames, 0);
    Message reply = decode(views, limits_);
    if (!seq || !reply.reply_to || *reply.reply_to == *seq) return reply;
    // A late reply to a request we gave up on: skip it (and remember it, in case nothing else comes).
    skipped_reply_to_.push_back(*reply.reply_to);
  }
}

Message Connection::request_raw(Message request, std::chrono::milliseconds deadline) {
  request.seq = next_seq_++;
  if (!send_message(socket_, request))
    throw TimeoutError(label_ + " took no '" + request.type + "' (seq " + std::to_string(request.seq) + "): there is no connection to it at " +
                       endpoint_ + " that a message can go out on. The security handshake fails where the server does not hold the key " +
                       "the run names (SPEC.md §2.1), or the server stopped reading");
  auto reply = await_reply(request.seq, deadline);
  if (!reply) {
    std::string why = label_ + " did not answer '" + request.type + "' (seq " + std::to_string(request.seq) + ") within " + seconds_text(deadline);
    if (!skipped_reply_to_.empty()) {
      why += "; it did send " + std::to_string(skipped_reply_to_.size()) + " repl" + (skipped_reply_to_.size() == 1 ? "y" : "ies") +
             " with reply_to " + std::to_string(skipped_reply_to_.back()) +
             ", which answer no request awaited now: a reply must carry its request's seq as reply_to (SPEC.md §3.1)";
    }
    throw TimeoutError(why);
  }
  return *reply;
}

Message Connection::request(Message request, std::chrono::milliseconds deadline) {
  const std::string type = request.type;
  Message reply = request_raw(std::move(request), deadline);
  if (reply.type == type::error)
    throw RemoteError(echoed(reply.body.value("code", "?")), echoed(reply.body.value("message", "(no message)"), kMaxEchoedMessageBytes),
                      echoed(reply.body.value("key", ""), kMaxEchoedPathBytes));
  return reply;
}

std::optional<Message> Connection::send_frames_raw(const std::vector<std::string>& frames, std::chrono::milliseconds deadline) {
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (!socket_.send(zmq::buffer(frames[i]), i + 1 < frames.size() ? zmq::send_flags::sndmore : zmq::send_flags::none))
      return std::nullopt;  // not taken (send_message): as unanswered
  return await_reply(std::nullopt, deadline);
}

SolverClient::SolverClient(zmq::context_t& context, const std::string& endpoint, std::string label, std::optional<std::string> server_key)
    : connection_(context, endpoint, std::move(label), Limits{}, std::move(server_key)) {}

bool SolverClient::Hello::has(std::string_view capability) const {
  for (const auto& c : capabilities)
    if (c == capability) return true;
  return false;
}

SolverClient::Hello SolverClient::hello(const std::string& client_name, std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::hello;
  request.body = {{"client", {{"name", client_name}, {"version", std::string(project_version())}}}};
  const Message reply = connection_.request(std::move(request), deadline);
  if (reply.type != type::hello_ok) throw RemoteError("BAD_MESSAGE", shape_mismatch(connection_.label(), "'" + echoed(reply.type) + "' to hello"), "");
  Hello hello;
  const auto& body = reply.body;
  try {
    hello.solver_name = body.at("solver").at("name").get<std::string>();
    hello.solver_version = body.at("solver").at("version").get<std::string>();
    hello.protocol_version = body.at("protocol_version").get<std::string>();
    hello.role = body.at("role").get<std::string>();
    hello.capabilities = body.at("capabilities").get<std::vector<std::string>>();
    if (const auto heartbeat = body.find(heartbeat::endpoint_key); heartbeat != body.end() && heartbeat->is_string())
      hello.heartbeat_endpoint = heartbeat->get<std::string>();
  } catch (const nlohmann::json::exception& e) {
    throw RemoteError("BAD_MESSAGE", connection_.label() + " sent a hello_ok without the fields SPEC.md §4.1 requires: " + e.what(), "");
  }
  return hello;
}

nlohmann::json SolverClient::configure(const std::string& section_json, std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::configure;
  request.body = {{"section_json", section_json}};
  const Message reply = connection_.request(std::move(request), deadline);
  const std::string expected = fnv1a64_hex(section_json);
  if (reply.body.value("scenario_hash", "") != expected)
    throw RemoteError("BAD_MESSAGE", connection_.label() + " reports scenario hash '" + reply.body.value("scenario_hash", "") +
                                         "' but the section sent hashes to '" + expected + "': it did not receive what was sent",
                      "");
  return reply.body;
}

InterfaceMesh SolverClient::get_interface(std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::get_interface;
  const Message reply = connection_.request(std::move(request), deadline);
  const Array* ids = find_array(reply.arrays, field::node_ids);
  const Array* facets = find_array(reply.arrays, field::facets);
  if (ids == nullptr || ids->shape.size() != 1 || facets == nullptr || facets->shape.size() != 2 || facets->shape[1] != 3)
    throw RemoteError("BAD_ARRAY", shape_mismatch(connection_.label(), "an interface without node_ids [n] and facets [m,3]"), "");
  InterfaceMesh mesh;
  mesh.node_ids = ids->to_i64();
  mesh.coordinates = require_f64(reply.arrays, field::coordinates, ids->shape[0], 3);
  mesh.facets = facets->to_i64();
  for (const auto index : mesh.facets)
    if (index < 0 || index >= mesh.node_count())
      throw RemoteError("BAD_ARRAY", shape_mismatch(connection_.label(), "facets referring to a node row that does not exist"), "");
  return mesh;
}

void SolverClient::set_interface(const InterfaceMesh& mesh, std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::set_interface;
  const std::int64_t n = mesh.node_count();
  request.arrays.push_back(Array::from_i64(field::node_ids, {n}, mesh.node_ids));
  request.arrays.push_back(Array::from_f64(field::coordinates, {n, 3}, mesh.coordinates));
  request.arrays.push_back(Array::from_i64(field::facets, {mesh.facet_count(), 3}, mesh.facets));
  (void)connection_.request(std::move(request), deadline);
}

Message SolverClient::advance(std::int64_t step, std::int64_t n_steps, double dt, std::vector<Array> inputs, std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::advance;
  request.step = step;
  request.body = {{"n_steps", n_steps}, {"dt", dt}};
  request.arrays = std::move(inputs);
  Message reply = connection_.request(std::move(request), deadline);
  if (reply.type != type::advanced || !reply.step || *reply.step != step + n_steps)
    throw RemoteError("STEP_MISMATCH", connection_.label() + " answered advance from step " + std::to_string(step) + " by " +
                                           std::to_string(n_steps) + " with step " + (reply.step ? std::to_string(*reply.step) : "none"),
                      "");
  return reply;
}

nlohmann::json SolverClient::query(std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::query;
  return connection_.request(std::move(request), deadline).body.value("monitors", nlohmann::json::object());
}

Message SolverClient::snapshot(std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::snapshot;
  return connection_.request(std::move(request), deadline);
}

std::int64_t SolverClient::checkpoint(const std::string& path, std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::checkpoint;
  request.body = {{"path", path}};
  const Message reply = connection_.request(std::move(request), deadline);
  if (reply.type != type::checkpointed || !reply.step)
    throw RemoteError("BAD_MESSAGE", connection_.label() + " answered checkpoint with '" + echoed(reply.type) + "' and no step", "");
  return *reply.step;
}

std::int64_t SolverClient::restore(const std::string& path, std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::restore;
  request.body = {{"path", path}};
  const Message reply = connection_.request(std::move(request), deadline);
  if (reply.type != type::restored || !reply.step)
    throw RemoteError("BAD_MESSAGE", connection_.label() + " answered restore with '" + echoed(reply.type) + "' and no step", "");
  return *reply.step;
}

void SolverClient::shutdown(std::chrono::milliseconds deadline) {
  Message request;
  request.type = type::shutdown;
  (void)connection_.request(std::move(request), deadline);
}

}  // namespace dfc::protocol
