#include "dfc/fdm/provider_interface.hpp"

#include <algorithm>
#include <cmath>

namespace dfc::fdm {

using protocol::Array;
using protocol::ErrorCode;
using protocol::ProtocolError;

protocol::InterfaceMesh provider_interface_mesh(const Mesh& mesh, std::span<const Index> gridpoints, std::string_view group) {
  std::vector<std::int64_t> row_of(mesh.gridpoint_count(), -1);
  protocol::InterfaceMesh out;
  for (std::size_t r = 0; r < gridpoints.size(); ++r) {
    const Index gp = gridpoints[r];
    row_of[gp] = std::int64_t(r);
    out.node_ids.push_back(std::int64_t(gp));
    out.coordinates.insert(out.coordinates.end(), {mesh.points[gp].x(), mesh.points[gp].y(), mesh.points[gp].z()});
  }
  // Each quad (right-hand normal out of the continuum) becomes two triangles
  // with the same orientation: (0,1,2) and (0,2,3).
  for (const FaceQuad& q : mesh.face_group(group))
    out.facets.insert(out.facets.end(), {row_of[q[0]], row_of[q[1]], row_of[q[2]], row_of[q[0]], row_of[q[2]], row_of[q[3]]});
  return out;
}

void require_finite(std::span<const double> values, std::string_view name) {
  for (const double v : values)
    if (!std::isfinite(v)) throw ProtocolError(ErrorCode::bad_array, "array '" + std::string(name) + "' contains a non-finite value");
}

ProviderInputs read_provider_inputs(std::span<const Array> inputs, std::int64_t rows, const std::string& who) {
  protocol::require_only(inputs, {protocol::field::force, protocol::field::mass}, who);
  ProviderInputs received;
  received.force = protocol::require_f64(inputs, protocol::field::force, rows, 3);
  require_finite(received.force, protocol::field::force);
  if (protocol::find_array(inputs, protocol::field::mass) != nullptr) {
    received.mass = protocol::require_f64(inputs, protocol::field::mass, rows, 0);
    for (const double m : *received.mass)
      if (!(m >= 0.0) || !std::isfinite(m))
        throw ProtocolError(ErrorCode::bad_array, "array 'mass' must hold finite masses >= 0 kg (f64 [" + std::to_string(rows) + "])");
  }
  return received;
}

}  // namespace dfc::fdm
