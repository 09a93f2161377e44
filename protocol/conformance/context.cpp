#include "context.hpp"

#include "dfc/protocol/authentication.hpp"
#include "dfc/protocol/message.hpp"
#include "dfc/protocol/transport.hpp"

namespace dfc::conformance {

namespace {
constexpr std::string_view kLoopbackPrefix = "tcp://127.0.0.1:";

bool is_port(std::string_view text) {
  if (text.empty() || text.size() > 5) return false;
  for (const char c : text)
    if (c < '0' || c > '9') return false;
  const int port = std::stoi(std::string(text));
  return port > 0 && port < 65536;
}
}  // namespace

Context::Context(Options options) : options_(std::move(options)), run_keys_(folder_.path()) {}

std::optional<std::string> Context::server_key() const {
  if (!authenticated_) return std::nullopt;
  return run_keys_.keys().public_key;
}

Subprocess& Context::server() {
  if (!server_) throw CheckFailure("the server was not started");
  return *server_;
}

void Context::start_server() {
  std::vector<std::string> argv = options_.command;
  argv.insert(argv.end(), {"--bind", "tcp://127.0.0.1:*"});
  try {
    server_ = std::make_unique<Subprocess>(argv, std::filesystem::path(), std::vector{run_keys_.environment_entry()});
  } catch (const std::exception& e) {
    throw CheckFailure(e.what());
  }
  auto line = server_->read_line(options_.timeout);
  authenticated_ = line && *line == protocol::authentication::kAnnouncement;
  if (authenticated_) line = server_->read_line(options_.timeout);
  if (!line) {
    // stdout closed early usually means the process is exiting: give it a moment to say how.
    if (const auto status = server_->wait_exit(std::chrono::milliseconds(500)))
      throw CheckFailure("the server " + Subprocess::describe_status(*status) + " without printing 'DFC-LISTENING <endpoint>'");
    throw CheckFailure("no line 'DFC-LISTENING <endpoint>' on stdout within " + std::to_string(options_.timeout.count()) +
                       " ms (is stdout flushed after it?)");
  }
  if (!line->starts_with(protocol::kListeningMarker))
    throw CheckFailure("the first stdout line must be 'DFC-LISTENING <endpoint>' (after '" + std::string(protocol::authentication::kAnnouncement) +
                       "' from a server that authenticates), got '" + line->substr(0, 200) + "'");
  endpoint_ = line->substr(protocol::kListeningMarker.size());
  if (!endpoint_.starts_with(kLoopbackPrefix) || !is_port(std::string_view(endpoint_).substr(kLoopbackPrefix.size())))
    throw CheckFailure("asked to bind tcp://127.0.0.1:*, the server reports '" + endpoint_ +
                       "'; expected the resolved endpoint tcp://127.0.0.1:<port>");
  connection_.emplace(zmq_context_, endpoint_, "the server", protocol::Limits{}, server_key());
  // Every wait polls the process, so a crash is reported at once instead of
  // after the full deadline (SPEC.md §9).
  connection_->set_wait_hook([this] { check_still_running(); });
}

void Context::check_still_running() {
  if (exit_expected_ || !server_) return;
  if (const auto status = server_->poll_exit()) throw ServerGone("the server " + Subprocess::describe_status(*status));
}

protocol::Message Context::request(protocol::Message request) {
  if (!connection_) throw CheckFailure("no connection to the server");
  return connection_->request_raw(std::move(request), options_.timeout);
}

protocol::Message Context::request(std::string_view type, nlohmann::json body) {
  protocol::Message message;
  message.type = std::string(type);
  message.body = std::move(body);
  return request(std::move(message));
}

protocol::Message Context::send_frames(const std::vector<std::string>& frames) {
  if (!connection_) throw CheckFailure("no connection to the server");
  auto reply = connection_->send_frames_raw(frames, options_.timeout);
  if (!reply) throw protocol::TimeoutError("no reply within " + std::to_string(options_.timeout.count()) + " ms");
  return *reply;
}

nlohmann::json Context::raw_header(std::string_view type) {
  return {{"protocol", protocol::kProtocolName}, {"version", protocol::version_string()}, {"type", type}, {"seq", next_raw_seq_++}};
}

void Context::expect_alive() {
  const protocol::Message reply = request(protocol::type::ping);
  if (reply.type != protocol::type::pong)
    throw CheckFailure("ping was answered by '" + reply.type + "' " + reply.body.dump() + " instead of 'pong'");
}

}  // namespace dfc::conformance
