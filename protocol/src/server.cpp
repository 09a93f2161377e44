#include "dfc/protocol/server.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <iostream>
#include <string_view>

#include "dfc/common/command_line.hpp"
#include "dfc/common/durations.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/common/json_text.hpp"
#include "dfc/common/version.hpp"
#include "dfc/protocol/heartbeat.hpp"
#include "dfc/protocol/heartbeat_responder.hpp"
#include "dfc/protocol/key_file.hpp"
#include "dfc/protocol/progress_gap_probe.hpp"
#include "dfc/protocol/server_session.hpp"
#include "dfc/protocol/transport.hpp"

namespace dfc::protocol {

namespace {

// libzmq's frame cap is 2 x the largest limit in an int64 (transport.cpp), and
// no array a solver sends needs more than 64 GiB.
constexpr std::uint64_t kLargestArrayLimit = std::uint64_t(1) << 36;

struct ServerOptions {
  std::string bind = "tcp://127.0.0.1:*";
  double idle_timeout_s = 3600.0;
  Limits limits;
};

void print_help(const ServerProgram& program) {
  std::cout << program.name << " — " << program.summary << "\n\n"
            << "Usage: " << program.name << " [--bind ENDPOINT] [--idle-timeout SECONDS] [--max-array-bytes N]\n"
            << (program.check_config ? "       " + program.name + " --check-config FILE.json\n" : std::string())
            << "       " << program.name << " --help | --version\n\n"
            << "A protocol v" << version_string() << " server (see protocol/SPEC.md). It binds a ZeroMQ ROUTER socket,\n"
            << "prints one line 'DFC-LISTENING <endpoint>' on stdout, and serves one client\n"
            << "(normally the coupler) until it receives 'shutdown'. Diagnostics go to stderr.\n"
            << "Beside it a second socket, the heartbeat, answers pings from a thread of its own,\n"
            << "also while the server works (announced in hello_ok; SPEC.md section 9.1).\n\n"
            << "Authentication (SPEC.md section 2.1): with " << authentication::kKeyFileVariable << "=FILE in its environment (a key file\n"
            << "of mode 0600: the coupler makes one per run; 'coupler keys FILE' makes one for a server started by hand)\n"
            << "every socket answers only clients that hold FILE (ZeroMQ CURVE), and the server prints\n"
            << "'" << authentication::kAnnouncement << "' before the DFC-LISTENING line. Without it any local process may connect.\n\n"
            << "Options:\n"
            << "  --bind ENDPOINT        where to listen (default tcp://127.0.0.1:* = loopback, any free port)\n"
            << "  --idle-timeout S       exit with status 3 after S seconds without any message (default 3600; 0 = never)\n"
            << "  --max-array-bytes N    largest array frame accepted (default 268435456)\n"
            << (program.check_config ? "  --check-config FILE    read FILE (a configure section, the scenario's participants.<name>.config) as\n"
                                       "                         configure would, without building the model; exit 0 if valid, 2 naming the key if not\n"
                                     : "")
            << program.extra_options
            << "  --help                 this text;  --version  solver and protocol versions\n\n"
            << "Configure section (the scenario part the coupler sends in 'configure'):\n"
            << program.config_help << "\n";
}

// --check-config FILE: the configure section in FILE through the program's
// parser (a ConfigError reaches run_server_main: exit 2 naming the key).
void check_config_file(const ServerProgram& program, const std::string& path) {
  if (!program.check_config) throw UserError(program.name + " has no --check-config");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw UserError("cannot read '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  const nlohmann::json section = parse_json_text(text.str(), JsonTextLimits{.reject_duplicate_keys = true});
  program.check_config(section);
  std::cout << path << ": a valid " << program.name << " configure section\n";
}

// Parses argv; returns an exit status if the program should stop now.
std::optional<int> parse_options(int argc, char** argv, const ServerProgram& program, ServerOptions& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UserError("option " + std::string(arg) + " needs a value; see --help");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      print_help(program);
      return 0;
    }
    if (arg == "--version") {
      std::cout << program.name << " " << project_version() << " (protocol " << version_string() << ")\n";
      return 0;
    }
    if (arg == "--check-config") {
      check_config_file(program, value());
      return 0;
    }
    if (arg == "--bind") options.bind = value();
    else if (arg == "--idle-timeout") options.idle_timeout_s = parse_number_option(arg, value(), Bounds{0.0, kLongestWaitSeconds});
    else if (arg == "--max-array-bytes") options.limits.max_array_bytes = parse_count_option(arg, value(), 1, kLargestArrayLimit);
    else throw UserError("unknown option '" + std::string(arg) + "'; see " + program.name + " --help");
  }
  return std::nullopt;
}

/// One line in the server's log at `shutdown`: the solver's share of the
/// advances and what handling the messages around them cost (decoding,
/// checks, encoding, sending), which bench/exchange_overhead.sh reads.
void print_advance_statistics(std::string_view name, const AdvanceStatistics& statistics, double service_seconds) {
  if (statistics.advances == 0) return;
  const double per_advance_us = 1e6 / static_cast<double>(statistics.advances);
  const double handling_s = std::max(0.0, service_seconds - statistics.solver_seconds);
  std::cerr << name << ": " << statistics.advances << " advances (" << statistics.steps << " steps): solver " << statistics.solver_seconds
            << " s (" << statistics.solver_seconds * per_advance_us << " us per advance), message handling " << handling_s << " s ("
            << handling_s * per_advance_us << " us per advance)";
  // The steady cost: the first advance (one-time work) apart. The steps of
  // the later advances are those of all but the first, assuming one size.
  if (statistics.advances > 1)
    std::cerr << "; first advance " << statistics.first_advance_seconds << " s, later ones "
              << (statistics.solver_seconds - statistics.first_advance_seconds) * 1e6 / static_cast<double>(statistics.advances - 1)
              << " us per advance";
  std::cerr << "\n";
}

/// The key pair of the key file named by DFC_KEY_FILE (SPEC.md §2.1), for a
/// server that declares 1.7 or later; nullopt when the variable is unset or
/// empty. A fixture playing an older server ignores it, as such a server would.
std::optional<authentication::CurveKeyPair> keys_from_environment(const ServerProgram& program) {
  if (program.declared_minor < authentication::kSinceMinor || !program.authentication) return std::nullopt;
  const char* path = std::getenv(std::string(authentication::kKeyFileVariable).c_str());
  if (path == nullptr || *path == '\0') return std::nullopt;
  try {
    return read_key_file(path);
  } catch (const UserError& e) {
    throw UserError(std::string(e.what()) + " (named by " + std::string(authentication::kKeyFileVariable) + ")");
  }
}

/// The heartbeat next to the main socket at `endpoint` (SPEC.md §9.1), for a
/// server that declares 1.6 or later and listens where one can sit beside it;
/// it requires the same key as the main socket (SPEC.md §2.1).
std::unique_ptr<HeartbeatResponder> start_heartbeat(zmq::context_t& context, const std::string& endpoint, const ServerProgram& program,
                                                    const Liveness& liveness, const std::string& version,
                                                    const std::optional<authentication::CurveKeyPair>& keys) {
  if (program.declared_minor < heartbeat::kSinceMinor || !program.heartbeat) return nullptr;
  const auto bind = heartbeat::bind_endpoint(endpoint);
  if (!bind) {
    std::cerr << program.name << ": no heartbeat beside " << endpoint << " (only tcp, ipc and inproc endpoints have one)\n";
    return nullptr;
  }
  return std::make_unique<HeartbeatResponder>(context, *bind, liveness, version, keys);
}

int serve(const ServerProgram& program, const ServerOptions& options) {
  const auto backend = program.make_backend();
  ServerSession session(*backend, options.limits);
  session.declare_minor(program.declared_minor);
  const auto keys = keys_from_environment(program);
  zmq::context_t context(1);
  zmq::socket_t socket(context, zmq::socket_type::router);
  configure_socket(socket, options.limits);
  authentication::secure_server_socket(socket, keys);
  socket.bind(options.bind);
  const std::string endpoint = socket.get(zmq::sockopt::last_endpoint);
  // Declared after the context and the socket, so destroyed before them on
  // every path out of here (return or exception): its thread stops and joins
  // first, and the context's termination never waits for its socket.
  Liveness liveness(program.declared_minor >= heartbeat::kProgressSinceMinor && program.progress);
  const auto heartbeat = start_heartbeat(context, endpoint, program, liveness, session.version(), keys);
  if (heartbeat) session.set_heartbeat_endpoint(heartbeat->endpoint());
  // Measures what run.stall_timeout_s must exceed, on request (docs/running.md); destroyed before `liveness`.
  std::optional<ProgressGapProbe> progress_gaps;
  if (const char* wanted = std::getenv(ProgressGapProbe::kVariable); wanted != nullptr && *wanted != '\0') progress_gaps.emplace(liveness, program.name);
  if (keys) std::cout << authentication::kAnnouncement << "\n";
  else if (program.declared_minor >= authentication::kSinceMinor && program.authentication)
    std::cerr << program.name << ": no " << authentication::kKeyFileVariable << " in the environment: any process on this host that reaches "
              << endpoint << " can talk to this server (SPEC.md section 2.1)\n";
  std::cout << kListeningMarker << endpoint << std::endl;

  const auto poll_slice = std::chrono::milliseconds(500);
  auto last_message = std::chrono::steady_clock::now();
  double advance_service_seconds = 0.0;  // from an advance request received to its reply sent
  while (!session.closed()) {
    auto frames = receive_frames(socket, poll_slice);
    if (!frames) {
      const double idle = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_message).count();
      if (options.idle_timeout_s > 0 && idle > options.idle_timeout_s) {
        std::cerr << program.name << ": no message for " << options.idle_timeout_s << " s (--idle-timeout); exiting\n";
        return 3;
      }
      continue;
    }
    last_message = std::chrono::steady_clock::now();
    if (frames->size() < 2) continue;  // a ROUTER message is [routing id, frames...]; nothing to answer
    const zmq::message_t& routing_id = frames->front();
    const auto views = frame_views(*frames, 1);
    Message reply;
    const std::int64_t advances_before = session.advance_statistics().advances;
    liveness.begin_request();
    try {
      reply = session.handle(decode(views, options.limits));
    } catch (const DecodeError& e) {
      reply = session.refuse_undecodable(e);
    }
    // Counted before the reply leaves: a client that pings right after the
    // reply must see it in `handled` (the checker's heartbeat.pong failed
    // now and then when the count came after the send).
    liveness.end_request(session.step());
    send_message(socket, reply, &routing_id);
    if (session.advance_statistics().advances != advances_before)
      advance_service_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - last_message).count();
  }
  print_advance_statistics(program.name, session.advance_statistics(), advance_service_seconds);
  // The sockets drop unsent messages on close (ZMQ_LINGER 0, so that no abort
  // path blocks); after `shutdown` give `bye` up to a second to leave (SPEC.md §2).
  socket.set(zmq::sockopt::linger, 1000);
  return 0;
}

}  // namespace

int run_server_main(int argc, char** argv, const ServerProgram& program) {
  try {
    ServerOptions options;
    if (const auto status = parse_options(argc, argv, program, options)) return *status;
    return serve(program, options);
  } catch (const UserError& e) {
    std::cerr << program.name << ": " << e.what() << "\n";
    return 2;
  } catch (const zmq::error_t& e) {
    std::cerr << program.name << ": ZeroMQ error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << program.name << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace dfc::protocol
