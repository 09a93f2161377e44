#include "dfc/fdm/grid_snapshot.hpp"

namespace dfc::fdm {

std::vector<protocol::Array> grid_snapshot(const Mesh& mesh, std::span<const Vec3> displacement, std::span<const Vec3> velocity,
                                           std::span<const Stress> zone_stress, std::span<const Vec3> external_force) {
  using protocol::Array;
  const auto n = std::int64_t(mesh.gridpoint_count());
  const auto m = std::int64_t(mesh.zone_count());
  const auto flatten = [](std::span<const Vec3> values) {
    std::vector<double> out;
    out.reserve(3 * values.size());
    for (const Vec3& v : values) out.insert(out.end(), {v.x(), v.y(), v.z()});
    return out;
  };
  std::vector<std::int64_t> zone_nodes;
  zone_nodes.reserve(8 * mesh.zone_count());
  for (const HexZone& zone : mesh.zones)
    for (const int corner : kVtkFromFlac) zone_nodes.push_back(std::int64_t(zone[std::size_t(corner)]));
  std::vector<double> stress;
  stress.reserve(6 * mesh.zone_count());
  for (const Stress& s : zone_stress) {
    // SPEC.md §6.4: the XDMF Tensor6 order xx, xy, xz, yy, yz, zz, so ParaView
    // labels the components right; the solver stores xx, yy, zz, xy, yz, zx.
    const auto c = s.components();
    stress.insert(stress.end(), {c[0], c[3], c[5], c[1], c[4], c[2]});
  }
  std::vector<Array> arrays;
  arrays.push_back(Array::from_f64("node_position", {n, 3}, flatten(mesh.points)));
  arrays.push_back(Array::from_f64("node_displacement", {n, 3}, flatten(displacement)));
  arrays.push_back(Array::from_f64("node_velocity", {n, 3}, flatten(velocity)));
  arrays.push_back(Array::from_i64("zone_nodes", {m, 8}, zone_nodes));
  arrays.push_back(Array::from_f64("zone_stress", {m, 6}, stress));
  if (!external_force.empty()) arrays.push_back(Array::from_f64("node_external_force", {n, 3}, flatten(external_force)));
  return arrays;
}

}  // namespace dfc::fdm
