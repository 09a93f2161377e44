#pragma once
// SolverBackend: what a solver implements to become a protocol v1 server.
//
// The generic server (server.hpp) owns the socket, the lifecycle state machine,
// step counting, limits and error replies (SPEC.md §5–§7); a backend only
// supplies the physics. dem_server, fdm_server and the reference continua are
// each one backend plus a five-line main().
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/protocol/array.hpp"
#include "dfc/protocol/error_code.hpp"

namespace dfc::protocol {

/// Names of the interface arrays (SPEC.md §6). Units SI.
namespace field {
inline constexpr const char* force = "force";                ///< f64 [n,3] N, force ON the continuum node / averaged force BY particles ON wall vertices
inline constexpr const char* velocity = "velocity";          ///< f64 [n,3] m/s, interface node velocity at the end of the advance
inline constexpr const char* displacement = "displacement";  ///< f64 [n,3] m, total interface node displacement since configure
inline constexpr const char* mass = "mass";                  ///< f64 [n] kg, extra inertial mass lumped at interface nodes (optional input)
inline constexpr const char* node_ids = "node_ids";          ///< i64 [n]
inline constexpr const char* coordinates = "coordinates";    ///< f64 [n,3] m
inline constexpr const char* facets = "facets";              ///< i64 [m,3] row indices into node_ids/coordinates
}  // namespace field

/// Capability strings announced in `hello_ok` (SPEC.md §4.1).
namespace capability {
inline constexpr const char* provides_interface = "provides_interface";  ///< answers get_interface; advance takes force, returns velocity
inline constexpr const char* accepts_interface = "accepts_interface";    ///< answers set_interface; advance takes velocity, returns force
inline constexpr const char* snapshot = "snapshot";
inline constexpr const char* checkpoint = "checkpoint";  ///< 1.3: answers checkpoint and restore (SPEC.md §4.7)
}  // namespace capability

struct SolverIdentity {
  std::string name;                       ///< e.g. "dem_server"
  std::string version;                    ///< the solver's own version
  std::string role;                       ///< "dem" or "continuum" (what it models)
  std::vector<std::string> capabilities;  ///< see capability::
};

/// The coupling boundary: nodes and triangular facets over them. Facet
/// normals (right-hand rule) point out of the continuum, into the DEM region.
struct InterfaceMesh {
  std::vector<std::int64_t> node_ids;
  std::vector<double> coordinates;    ///< 3 per node, m
  std::vector<std::int64_t> facets;   ///< 3 per facet, row indices into node_ids
  [[nodiscard]] std::int64_t node_count() const noexcept { return std::int64_t(node_ids.size()); }
  [[nodiscard]] std::int64_t facet_count() const noexcept { return std::int64_t(facets.size() / 3); }
};

struct AdvanceRequest {
  std::int64_t first_step = 0;  ///< the server's step count before this advance
  std::int64_t n_steps = 1;     ///< >= 1
  double dt = 0.0;              ///< s, > 0; time after the advance is (first_step + n_steps) * dt only if dt never changed
  std::vector<Array> inputs;    ///< interface fields (SPEC.md §6); empty when uncoupled
};

struct AdvanceResult {
  std::vector<Array> outputs;  ///< interface fields (SPEC.md §6)
  nlohmann::json monitors = nlohmann::json::object();  ///< scalar or [x,y,z] monitors (SPEC.md §6.3)
};

class SolverBackend {
 public:
  virtual ~SolverBackend() = default;

  [[nodiscard]] virtual SolverIdentity identity() const = 0;

  /// Validates and applies the scenario section. Throws dfc::ConfigError with
  /// a key path relative to the section. Returns information for the coupler:
  /// at least {"dt_suggested": s} and {"dt_max": s or null when any dt is
  /// stable (mass scaling)}.
  virtual nlohmann::json configure(const nlohmann::json& section) = 0;

  /// The coupling boundary (capability provides_interface).
  virtual InterfaceMesh interface_mesh() {
    throw ProtocolError(ErrorCode::unsupported, "this server does not provide an interface mesh");
  }
  /// Installs the coupling boundary received from the other side (capability accepts_interface).
  virtual void set_interface(const InterfaceMesh& /*mesh*/) {
    throw ProtocolError(ErrorCode::unsupported, "this server does not accept an interface mesh");
  }

  /// Runs request.n_steps steps. Throws ProtocolError (bad_array for wrong
  /// inputs) or dfc::SolverError (becomes solver_failure).
  virtual AdvanceResult advance(const AdvanceRequest& request) = 0;

  /// Current monitors (same keys as in AdvanceResult).
  [[nodiscard]] virtual nlohmann::json monitors() = 0;

  /// Full state for output (SPEC.md §6.4). `kind` is set to "particles" or "grid".
  [[nodiscard]] virtual std::vector<Array> snapshot(std::string& kind) = 0;

  /// Capability checkpoint (SPEC.md §4.7): every member that changes while the
  /// solver runs, as bytes (dfc/common/state_archive.hpp); what configure and
  /// the interface set up from the section is not stored, it is rebuilt.
  [[nodiscard]] virtual std::string checkpoint_state() {
    throw ProtocolError(ErrorCode::unsupported, "this server cannot write checkpoints (it lacks capability 'checkpoint')");
  }
  /// Restores checkpoint_state()'s bytes into a server configured (and given
  /// its interface) as the one that wrote them. Throws dfc::StateFormatError
  /// or ProtocolError(bad_checkpoint) for bytes that do not fit this model.
  virtual void restore_state(std::string_view /*bytes*/) {
    throw ProtocolError(ErrorCode::unsupported, "this server cannot restore checkpoints (it lacks capability 'checkpoint')");
  }
};

}  // namespace dfc::protocol
