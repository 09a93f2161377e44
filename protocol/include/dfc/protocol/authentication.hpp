#pragma once
// Authentication (SPEC.md §2.1, 1.7): who may talk to a server. A server
// given a key file (its path in the environment variable DFC_KEY_FILE) makes
// every socket it binds a ZeroMQ CURVE server with the key; only a client that
// holds the same file can complete the handshake. A peer without it gets no
// answer: libzmq drops it during the handshake, before any message reaches
// the server's threads. What both sides share: the version, the names and
// the socket options.
#include <optional>
#include <string>
#include <string_view>

#include <zmq.hpp>

namespace dfc::protocol::authentication {

/// The minor version (of major 1) from which a server authenticates its peers.
inline constexpr int kSinceMinor = 7;

/// The environment variable that names a server's key file. An environment
/// variable, not an option: a server that does not know it (an older or
/// third-party one) starts as before, and the key itself never appears in a
/// command line (`ps`, /proc/PID/cmdline), only the path of a file that only
/// its owner may read.
inline constexpr std::string_view kKeyFileVariable = "DFC_KEY_FILE";

/// The stdout line an authenticating server prints before `DFC-LISTENING`:
/// its client must connect with the key (SPEC.md §2.1).
inline constexpr std::string_view kAnnouncement = "DFC-AUTHENTICATION curve";

/// A CURVE key pair, Z85 text (40 characters each). The server's pair is the
/// run's secret: its public key never goes on the wire (CurveZMQ's client
/// must know it beforehand), and knowing it is what lets a client complete
/// the handshake, so it is kept as secret as the secret key.
struct CurveKeyPair {
  std::string public_key;
  std::string secret_key;
};

/// A fresh key pair (libzmq's zmq_curve_keypair, from libsodium's random source).
[[nodiscard]] CurveKeyPair generate_key_pair();

/// Makes `socket` a CURVE server with `server_keys`; call before bind. No-op
/// without keys (the NULL mechanism: anyone who reaches the endpoint).
void secure_server_socket(zmq::socket_t& socket, const std::optional<CurveKeyPair>& server_keys);

/// Makes `socket` a CURVE client of the server whose key is `server_public`,
/// with a key pair of its own made here (the server accepts any client that
/// knows its key); call before connect. No-op without a key.
void secure_client_socket(zmq::socket_t& socket, const std::optional<std::string>& server_public);

}  // namespace dfc::protocol::authentication
