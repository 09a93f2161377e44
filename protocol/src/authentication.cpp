#include "dfc/protocol/authentication.hpp"

#include <array>
#include <stdexcept>

namespace dfc::protocol::authentication {

namespace {

/// 32-byte keys as Z85 text: 40 characters and the terminating NUL.
using Z85Key = std::array<char, 41>;

void check_curve_available() {
  if (zmq_has("curve") == 0)
    throw std::runtime_error("this libzmq was built without CURVE (zmq_has(\"curve\") is false); install one built with libsodium");
}

}  // namespace

CurveKeyPair generate_key_pair() {
  check_curve_available();
  Z85Key public_key{};
  Z85Key secret_key{};
  if (zmq_curve_keypair(public_key.data(), secret_key.data()) != 0) throw zmq::error_t();
  return {public_key.data(), secret_key.data()};
}

void secure_server_socket(zmq::socket_t& socket, const std::optional<CurveKeyPair>& server_keys) {
  if (!server_keys) return;
  check_curve_available();
  socket.set(zmq::sockopt::curve_server, 1);
  socket.set(zmq::sockopt::curve_secretkey, server_keys->secret_key);
}

void secure_client_socket(zmq::socket_t& socket, const std::optional<std::string>& server_public) {
  if (!server_public) return;
  // A pair of the client's own per socket: the server accepts any client key
  // (no ZAP handler), since proving knowledge of the server's key is the test.
  const CurveKeyPair own = generate_key_pair();
  socket.set(zmq::sockopt::curve_serverkey, *server_public);
  socket.set(zmq::sockopt::curve_publickey, own.public_key);
  socket.set(zmq::sockopt::curve_secretkey, own.secret_key);
}

}  // namespace dfc::protocol::authentication
