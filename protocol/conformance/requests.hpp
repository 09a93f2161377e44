#pragma once
// Well-formed requests the checks send (and deliberately bend).
#include <cstdint>
#include <string>
#include <vector>

#include "dfc/protocol/message.hpp"

namespace dfc::conformance {

class Context;

/// hello from the checker, speaking `version`.
[[nodiscard]] protocol::Message hello_request(std::string version);

/// advance from `step` by `n_steps` of `dt`, with no arrays.
[[nodiscard]] protocol::Message advance_request(std::int64_t step, std::int64_t n_steps, double dt);

/// The same with zero_inputs(context, extra_rows) as its arrays.
[[nodiscard]] protocol::Message advance_with_zero_inputs(const Context& context, std::int64_t step, std::int64_t n_steps, double dt,
                                                         std::int64_t extra_rows = 0);

/// set_interface with the test mesh: a unit square in z = 0 as two
/// triangles (normal +z), node ids 101..104 so that ids and rows differ.
[[nodiscard]] protocol::Message test_mesh_request();
inline constexpr std::int64_t kTestMeshNodes = 4;

/// True when advance takes interface inputs (provides or accepts the interface).
[[nodiscard]] bool takes_inputs(const Context& context);

/// Zero-valued advance inputs per SPEC.md §6.1 (force for a provider,
/// velocity for an acceptor), `extra_rows` longer than the interface.
/// Throws CheckFailure ("not run") when the interface size is unknown
/// because the interface exchange failed or was rejected.
[[nodiscard]] std::vector<protocol::Array> zero_inputs(const Context& context, std::int64_t extra_rows = 0);

}  // namespace dfc::conformance
