// zmq_round_trip — the floor under the cost of one coupling exchange: the
// wall time of one protocol round trip between two processes on this machine,
// with messages shaped like an exchange's (an `advance` carrying one [n,3] f64
// array and an `advanced` reply carrying one [n,3] array and a body of
// monitors), through the same transport and codec the coupler and the servers
// use (DEALER to ROUTER over loopback TCP, protocol/src/transport.cpp).
// A serial exchange makes two such round trips, one per participant
// (coupler/src/serial_coupling_scheme.cpp); bench/exchange_overhead.sh
// compares the measured exchange overhead with twice this figure.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <zmq.hpp>

#include "dfc/common/command_line.hpp"
#include "dfc/common/errors.hpp"
#include "dfc/protocol/authentication.hpp"
#include "dfc/protocol/codec.hpp"
#include "dfc/protocol/message.hpp"
#include "dfc/protocol/transport.hpp"

namespace {

using dfc::protocol::Array;
using dfc::protocol::Message;

struct Options {
  std::int64_t round_trips = 20'000;
  std::int64_t nodes = 112;     ///< interface nodes: the demo's 112
  std::int64_t monitors = 40;   ///< scalar monitors in each reply (the DEM's pile run sends about 40)
  std::string bind = "tcp://127.0.0.1:*";  ///< the coupler's servers bind loopback TCP by default
  double work_us = 0.0;  ///< the child computes this long before each reply, as a solver would (not counted)
  /// CURVE, as the coupler's servers since protocol 1.7 (SPEC.md §2.1), or NULL (no authentication, as before).
  bool curve = true;
  dfc::protocol::authentication::CurveKeyPair server_keys;  ///< made before the fork, so both processes hold them
};

/// Keeps the CPU busy for `microseconds`, as a solver's step would.
void compute_for(double microseconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double, std::micro>(microseconds);
  while (std::chrono::steady_clock::now() < until) {
  }
}

void print_help() {
  std::cout << "zmq_round_trip — wall time of one protocol round trip between two processes\n\n"
               "Usage: zmq_round_trip [--round-trips N] [--nodes N] [--monitors N] [--server-work-us T] [--bind ENDPOINT]\n"
               "                      [--mechanism curve|null]\n\n"
               "A child process serves a ROUTER socket on loopback TCP; the parent sends N advance-like\n"
               "requests (one [nodes,3] f64 array) and waits for each advanced-like reply (one [nodes,3]\n"
               "array and `monitors` numbers), as the coupler does with each server. Prints the mean,\n"
               "the median and the 90th percentile in microseconds. With --server-work-us the child computes for T us\n"
               "before each reply, as a solver does, and T is not counted: while it computes, the parent sleeps\n"
               "in its receive, and waking it is part of what a round trip costs.\n"
               "--mechanism: ZeroMQ CURVE, as the coupler and the servers it starts use since protocol 1.7, or NULL\n"
               "(no authentication, as before 1.7; SPEC.md section 2.1).\n"
               "Defaults: --round-trips 20000 --nodes 112 --monitors 40 --bind tcp://127.0.0.1:* (ipc://PATH: a Unix socket)\n"
               "--mechanism curve.\n";
}

Message advance_like(std::int64_t seq, std::int64_t nodes) {
  Message request;
  request.type = std::string(dfc::protocol::type::advance);
  request.seq = seq;
  request.step = seq;
  request.body = {{"n_steps", 1}, {"dt", 1e-6}};
  const std::vector<double> velocities(static_cast<std::size_t>(3 * nodes), 1e-3);
  request.arrays.push_back(Array::from_f64("interface_velocity", {nodes, 3}, velocities));
  return request;
}

Message advanced_like(const Message& request, std::int64_t nodes, std::int64_t monitors) {
  Message reply;
  reply.type = std::string(dfc::protocol::type::advanced);
  reply.seq = request.seq;
  reply.reply_to = request.seq;
  reply.step = request.seq + 1;
  nlohmann::json values = nlohmann::json::object();
  for (std::int64_t i = 0; i < monitors; ++i) values["monitor_" + std::to_string(i)] = 0.1234567890123 * static_cast<double>(i);
  reply.body = {{"monitors", std::move(values)}};
  const std::vector<double> forces(static_cast<std::size_t>(3 * nodes), -2.5);
  reply.arrays.push_back(Array::from_f64("interface_force", {nodes, 3}, forces));
  return reply;
}

/// The child: answers every request until it has answered `round_trips` of them.
int serve(int endpoint_pipe, const Options& options) {
  zmq::context_t context(1);
  zmq::socket_t socket(context, zmq::socket_type::router);
  const dfc::protocol::Limits limits;
  dfc::protocol::configure_socket(socket, limits);
  dfc::protocol::authentication::secure_server_socket(socket, options.curve ? std::optional(options.server_keys) : std::nullopt);
  socket.bind(options.bind);
  const std::string endpoint = socket.get(zmq::sockopt::last_endpoint);
  if (::write(endpoint_pipe, endpoint.c_str(), endpoint.size() + 1) < 0) return 1;
  ::close(endpoint_pipe);
  for (std::int64_t answered = 0; answered < options.round_trips;) {
    auto frames = dfc::protocol::receive_frames(socket, std::chrono::seconds(30));
    if (!frames) return 1;
    const Message request = dfc::protocol::decode(dfc::protocol::frame_views(*frames, 1), limits);
    compute_for(options.work_us);
    dfc::protocol::send_message(socket, advanced_like(request, options.nodes, options.monitors), &frames->front());
    ++answered;
  }
  socket.set(zmq::sockopt::linger, 1000);  // let the last reply leave
  return 0;
}

int measure(const std::string& endpoint, const Options& options) {
  zmq::context_t context(1);
  zmq::socket_t socket(context, zmq::socket_type::dealer);
  const dfc::protocol::Limits limits;
  dfc::protocol::configure_socket(socket, limits);
  dfc::protocol::authentication::secure_client_socket(socket, options.curve ? std::optional(options.server_keys.public_key) : std::nullopt);
  socket.connect(endpoint);
  std::vector<double> microseconds;
  microseconds.reserve(static_cast<std::size_t>(options.round_trips));
  for (std::int64_t seq = 0; seq < options.round_trips; ++seq) {
    const auto start = std::chrono::steady_clock::now();
    dfc::protocol::send_message(socket, advance_like(seq, options.nodes));
    auto frames = dfc::protocol::receive_frames(socket, std::chrono::seconds(30));
    if (!frames) throw std::runtime_error("no reply within 30 s");
    const Message reply = dfc::protocol::decode(dfc::protocol::frame_views(*frames, 0), limits);
    if (reply.reply_to != seq) throw std::runtime_error("reply out of order");
    microseconds.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() - options.work_us);
  }
  // The first round trips include the connection's set-up: the figures are of the rest.
  const std::size_t warm_up = std::min<std::size_t>(microseconds.size() / 10, 100);
  std::vector<double> steady(microseconds.begin() + static_cast<std::ptrdiff_t>(warm_up), microseconds.end());
  double sum = 0.0;
  for (const double value : steady) sum += value;
  std::sort(steady.begin(), steady.end());
  const auto percentile = [&](double p) { return steady[static_cast<std::size_t>(p * static_cast<double>(steady.size() - 1))]; };
  std::printf("round trips %zu (after %zu warm-up), nodes %lld, monitors %lld, mechanism %s\n", steady.size(), warm_up,
              static_cast<long long>(options.nodes), static_cast<long long>(options.monitors), options.curve ? "curve" : "null");
  std::printf("round_trip_us mean %.1f median %.1f p90 %.1f\n", sum / static_cast<double>(steady.size()), percentile(0.5), percentile(0.9));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    Options options;
    for (int i = 1; i < argc; ++i) {
      const std::string_view arg = argv[i];
      if (arg == "--help" || arg == "-h") {
        print_help();
        return 0;
      }
      if (i + 1 >= argc) throw dfc::UserError("option " + std::string(arg) + " needs a value; see --help");
      const std::string value = argv[++i];
      if (arg == "--round-trips") options.round_trips = static_cast<std::int64_t>(dfc::parse_count_option(arg, value, 10, 100'000'000));
      else if (arg == "--nodes") options.nodes = static_cast<std::int64_t>(dfc::parse_count_option(arg, value, 1, 10'000'000));
      else if (arg == "--bind") options.bind = value;
      else if (arg == "--server-work-us") options.work_us = dfc::parse_number_option(arg, value, dfc::Bounds{0.0, 1e6});
      else if (arg == "--monitors") options.monitors = static_cast<std::int64_t>(dfc::parse_count_option(arg, value, 0, 10'000));
      else if (arg == "--mechanism" && (value == "curve" || value == "null")) options.curve = value == "curve";
      else if (arg == "--mechanism") throw dfc::UserError("--mechanism takes curve or null, not '" + value + "'");
      else throw dfc::UserError("unknown option '" + std::string(arg) + "'; see --help");
    }
    if (options.curve) options.server_keys = dfc::protocol::authentication::generate_key_pair();
    int endpoint_pipe[2];
    if (::pipe(endpoint_pipe) != 0) throw std::runtime_error("pipe failed");
    const pid_t child = ::fork();
    if (child < 0) throw std::runtime_error("fork failed");
    if (child == 0) {
      ::close(endpoint_pipe[0]);
      std::_Exit(serve(endpoint_pipe[1], options));
    }
    ::close(endpoint_pipe[1]);
    std::string endpoint;
    char c = 0;
    while (::read(endpoint_pipe[0], &c, 1) == 1 && c != '\0') endpoint.push_back(c);
    ::close(endpoint_pipe[0]);
    const int status = measure(endpoint, options);
    int child_status = 0;
    ::waitpid(child, &child_status, 0);
    return status != 0 ? status : (WIFEXITED(child_status) ? WEXITSTATUS(child_status) : 1);
  } catch (const dfc::UserError& e) {
    std::cerr << "zmq_round_trip: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "zmq_round_trip: " << e.what() << "\n";
    return 1;
  }
}
