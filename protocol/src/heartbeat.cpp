#include "dfc/protocol/heartbeat.hpp"

namespace dfc::protocol::heartbeat {

namespace {
constexpr std::string_view kTcp = "tcp://";

/// "HOST" of "tcp://HOST:PORT" (with brackets for IPv6), or nullopt.
std::optional<std::string_view> tcp_host(std::string_view endpoint) {
  if (!endpoint.starts_with(kTcp)) return std::nullopt;
  const std::string_view address = endpoint.substr(kTcp.size());
  const auto colon = address.rfind(':');
  if (colon == std::string_view::npos || colon == 0) return std::nullopt;
  return address.substr(0, colon);
}
}  // namespace

Limits message_limits() {
  Limits limits;
  limits.max_header_bytes = 64u << 10;
  limits.max_array_bytes = 0;
  limits.max_arrays = 0;
  return limits;
}

std::optional<std::string> bind_endpoint(std::string_view main) {
  if (const auto host = tcp_host(main)) return std::string(kTcp) + std::string(*host) + ":*";
  for (const std::string_view scheme : {"ipc://", "inproc://"})
    if (main.starts_with(scheme) && main.size() > scheme.size()) return std::string(main) + ".heartbeat";
  return std::nullopt;
}

std::string connect_endpoint(std::string_view announced, std::string_view main) {
  const auto host = tcp_host(announced);
  const auto main_host = tcp_host(main);
  if (!host || !main_host || (*host != "0.0.0.0" && *host != "*" && *host != "[::]")) return std::string(announced);
  const std::string_view port = announced.substr(kTcp.size() + host->size());  // ":PORT"
  return std::string(kTcp) + std::string(*main_host) + std::string(port);
}

}  // namespace dfc::protocol::heartbeat
