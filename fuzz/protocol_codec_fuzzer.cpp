// libFuzzer harness for the protocol codec and the server's session state
// machine (SPEC.md §3, §5, §8). Each input is a sequence of messages, each
// split into frames (fuzz_input.hpp); every message goes the way the server's
// loop sends it (protocol/src/server.cpp): decode, then ServerSession::handle,
// or refuse_undecodable when decode throws DecodeError, the codec's one
// documented way of refusing bytes. Any other exception escapes and aborts,
// which libFuzzer reports as a crash.
//
// Beyond "no crash, no sanitizer report" it checks what SPEC.md promises:
// - a decoded message encodes and decodes back to the same message;
// - a decoded array's frame holds exactly product(shape) × size(dtype) bytes;
// - the server numbers its replies 0, 1, 2, ... and each names the request's
//   seq (none for a message whose seq could not be read);
// - every reply is itself a valid message (it encodes, and decodes to itself);
// - no reply is INTERNAL (a bug in the server, SPEC.md §7), and a successful
//   reply has the request's reply type and moves the session as §5.1 says.
// A broken promise traps, so libFuzzer keeps the input.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dfc/protocol/codec.hpp"
#include "dfc/protocol/message.hpp"
#include "dfc/protocol/server_session.hpp"
#include "fuzz_backend.hpp"
#include "fuzz_input.hpp"

namespace {

using dfc::protocol::Message;
using dfc::protocol::SessionState;
namespace type = dfc::protocol::type;

[[noreturn]] void broken(const std::string& promise) {
  std::fprintf(stderr, "protocol_codec_fuzzer: broken promise: %s\n", promise.c_str());
  __builtin_trap();
}

void require(bool holds, const std::string& promise) {
  if (!holds) broken(promise);
}

bool same_message(const Message& a, const Message& b) {
  if (a.type != b.type || a.version != b.version || a.seq != b.seq || a.reply_to != b.reply_to || a.step != b.step || a.body != b.body ||
      a.arrays.size() != b.arrays.size())
    return false;
  for (std::size_t k = 0; k < a.arrays.size(); ++k) {
    const auto& x = a.arrays[k];
    const auto& y = b.arrays[k];
    if (x.name != y.name || x.dtype != y.dtype || x.shape != y.shape || x.bytes != y.bytes) return false;
  }
  return true;
}

/// `body` as encode_header sends it: error texts may quote bytes of a request
/// that are not UTF-8, and those go out as U+FFFD.
nlohmann::json as_sent(const nlohmann::json& body) {
  return nlohmann::json::parse(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

/// `message` encoded as the frames a socket would carry, and decoded again.
Message encode_and_decode(const Message& message, const dfc::protocol::Limits& limits) {
  const std::string header = dfc::protocol::encode_header(message);
  std::vector<std::span<const std::byte>> frames{std::as_bytes(std::span(header.data(), header.size()))};
  for (const auto& array : message.arrays) frames.emplace_back(array.bytes);
  return dfc::protocol::decode(frames, limits);
}

void check_decoded(const Message& request, const dfc::protocol::Limits& limits) {
  for (const auto& array : request.arrays) {
    require(array.shape.size() <= 8, "a decoded shape has at most 8 extents");
    require(std::uint64_t(array.element_count()) * dfc::protocol::dtype_size(array.dtype) == array.bytes.size(),
            "a decoded array's frame holds product(shape) x size(dtype) bytes");
  }
  // The header may grow when re-encoded ("1E5" is written "100000.0"), so
  // only its own limit is lifted; the arrays' limits still apply.
  dfc::protocol::Limits relaxed = limits;
  relaxed.max_header_bytes = std::numeric_limits<std::size_t>::max();
  Message again;
  try {
    again = encode_and_decode(request, relaxed);
  } catch (const dfc::protocol::DecodeError& e) {
    broken(std::string("a decoded message decodes again after encoding, but: ") + e.what());
  }
  require(same_message(request, again), "a decoded message encodes and decodes to the same message");
}

void check_reply(const Message& reply, std::int64_t expected_seq, std::optional<std::int64_t> request_seq) {
  require(reply.seq == expected_seq, "the server numbers its replies 0, 1, 2, ...");
  require(reply.reply_to == request_seq, "a reply names the request's seq, or none when it could not be read");
  if (reply.type == type::error) {
    const auto code = reply.body.find("code");
    require(code != reply.body.end() && code->is_string(), "an error reply has body.code");
    const auto known = dfc::protocol::error_code_from_name(code->get<std::string>());
    require(known.has_value(), "an error reply's code is one of SPEC.md §7");
    if (*known == dfc::protocol::ErrorCode::internal) broken("no reply is INTERNAL (a bug in the server): " + as_sent(reply.body).dump());
  }
  Message decoded;
  try {
    decoded = encode_and_decode(reply, dfc::protocol::Limits{});
  } catch (const dfc::protocol::DecodeError& e) {
    broken(std::string("a reply decodes under the default limits, but: ") + e.what());
  }
  Message sent = reply;
  sent.body = as_sent(reply.body);
  require(same_message(sent, decoded), "a reply encodes and decodes to itself");
}

/// The successful reply to each request type and the state it leaves (SPEC.md §4, §5.1); nullopt: unchanged.
struct Transition {
  std::string_view request;
  std::string_view reply;
  std::optional<SessionState> state;
};
constexpr Transition kTransitions[] = {
    {type::hello, type::hello_ok, SessionState::greeted},
    {type::configure, type::configured, SessionState::configured},
    {type::get_interface, type::interface, std::nullopt},
    {type::set_interface, type::ok, std::nullopt},
    {type::advance, type::advanced, SessionState::running},
    {type::query, type::monitors, std::nullopt},
    {type::snapshot, type::snapshot_data, std::nullopt},
    {type::ping, type::pong, std::nullopt},
    {type::shutdown, type::bye, SessionState::closed},
};

void check_transition(const Message& request, const Message& reply, SessionState before, std::int64_t step_before,
                      const dfc::protocol::ServerSession& session) {
  if (reply.type == type::error) {
    // An error changes nothing, except that a solver failure fails the session (§5.1).
    const bool solver_failure = reply.body.value("code", "") == "SOLVER_FAILURE" && !reply.body.contains("dt_max");
    require(session.step() == step_before, "an error reply leaves the step");
    require(session.state() == before || (solver_failure && session.state() == SessionState::failed),
            "an error reply leaves the state, unless the solver failed");
    return;
  }
  for (const auto& t : kTransitions) {
    if (t.request != request.type) continue;
    require(reply.type == t.reply, "request '" + request.type + "' is answered by '" + std::string(t.reply) + "' or an error");
    require(session.state() == t.state.value_or(before), "'" + request.type + "' moves the session as SPEC.md §5.1 says");
    if (reply.type == type::advanced)
      require(reply.step == session.step() && session.step() == step_before + request.body.at("n_steps").get<std::int64_t>(),
              "advanced.step is the step before plus n_steps");
    return;
  }
  broken("request type '" + request.type + "' succeeded but is not one this backend can answer");
}

/// DFC_FUZZ_TRACE=1: one line per message, to read what a crash input does.
void trace(std::string_view request, const Message& reply, const dfc::protocol::ServerSession& session) {
  static const bool on = std::getenv("DFC_FUZZ_TRACE") != nullptr;
  if (!on) return;
  const std::string what = reply.type == type::error ? std::string(reply.body.value("code", "?")) + ": " + as_sent(reply.body).value("message", "")
                                                     : reply.type;
  std::fprintf(stderr, "%.*s -> %s [%s, step %lld]\n", int(request.size()), request.data(), what.c_str(),
               std::string(dfc::protocol::session_state_name(session.state())).c_str(), static_cast<long long>(session.step()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  dfc::fuzz::FuzzBackend backend;
  dfc::protocol::ServerSession session(backend, dfc::protocol::Limits{});
  std::int64_t next_reply_seq = 0;
  for (const std::string_view bytes : dfc::fuzz::split_messages(input)) {
    if (session.closed()) break;  // the server exits after `bye`
    const dfc::fuzz::FuzzFrames message = dfc::fuzz::read_frames(bytes);
    const SessionState before = session.state();
    const std::int64_t step_before = session.step();
    std::optional<Message> request;
    Message reply;
    try {
      request = dfc::protocol::decode(message.frames, message.limits);
    } catch (const dfc::protocol::DecodeError& e) {
      reply = session.refuse_undecodable(e);
      trace("(undecodable)", reply, session);
      check_reply(reply, next_reply_seq++, e.seq());
      require(session.state() == before && session.step() == step_before, "an undecodable message changes nothing");
      continue;
    }
    check_decoded(*request, message.limits);
    reply = session.handle(*request);
    trace(request->type, reply, session);
    check_reply(reply, next_reply_seq++, request->seq);
    check_transition(*request, reply, before, step_before, session);
  }
  return 0;
}
