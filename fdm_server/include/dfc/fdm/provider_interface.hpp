#pragma once
// The provider side of the coupling interface (SPEC.md §6, docs/theory/coupling.md §3), shared
// by every continuum that offers the fdm_server interface: fdm_server itself
// and the reference continua built on the same mesh.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dfc/fdm/mesh.hpp"
#include "dfc/protocol/solver_backend.hpp"

namespace dfc::fdm {

/// The interface of face group `group`: node ids = gridpoint indices in the
/// order of `gridpoints` (the rows of every interface array), each quad split
/// into the triangles (0,1,2) and (0,2,3), normals out of the continuum.
[[nodiscard]] protocol::InterfaceMesh provider_interface_mesh(const Mesh& mesh, std::span<const Index> gridpoints, std::string_view group);

/// What a provider receives with advance.
struct ProviderInputs {
  std::vector<double> force;                ///< f64 [n,3], N, force ON each interface node
  std::optional<std::vector<double>> mass;  ///< f64 [n], kg, extra inertial mass, when sent
};

/// Validates the inputs of a provider's advance: only `force` (required,
/// finite) and `mass` (optional, finite, >= 0) for `rows` interface nodes.
/// Throws ProtocolError(bad_array) naming the array; `who` names the receiver
/// in the message ("a provider fdm_server").
[[nodiscard]] ProviderInputs read_provider_inputs(std::span<const protocol::Array> inputs, std::int64_t rows, const std::string& who);

/// Throws ProtocolError(bad_array) when `values` of array `name` holds a NaN or infinity.
void require_finite(std::span<const double> values, std::string_view name);

}  // namespace dfc::fdm
