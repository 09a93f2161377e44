#include "dfc/fdm/tetrahedron.hpp"

#include <algorithm>

namespace dfc::fdm {

double signed_tetrahedron_volume(const Vec3& x1, const Vec3& x2, const Vec3& x3, const Vec3& x4) {
  return (x2 - x1).dot((x3 - x1).cross(x4 - x1)) / 6.0;
}

Tetrahedron make_tetrahedron(const std::array<Index, 4>& nodes, const std::array<Vec3, 4>& x) {
  Tetrahedron tet;
  tet.nodes = nodes;
  tet.volume = signed_tetrahedron_volume(x[0], x[1], x[2], x[3]);
  for (std::size_t n = 0; n < 4; ++n) {
    const Vec3& a = x[(n + 1) % 4];
    const Vec3& b = x[(n + 2) % 4];
    const Vec3& c = x[(n + 3) % 4];
    Vec3 area = 0.5 * (b - a).cross(c - a);
    // §1.3: a⁽ⁿ⁾ points away from node n.
    if (area.dot((a + b + c) / 3.0 - x[n]) < 0.0) area = -area;
    tet.area[n] = area;
  }
  return tet;
}

Eigen::Matrix3d velocity_gradient(const Tetrahedron& tet, std::span<const Vec3> velocity) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (std::size_t n = 0; n < 4; ++n) sum += velocity[tet.nodes[n]] * tet.area[n].transpose();
  return sum * (-1.0 / (3.0 * tet.volume));
}

SymTensor strain_rate(const Tetrahedron& tet, std::span<const Vec3> velocity) {
  return SymTensor::symmetric_part(velocity_gradient(tet, velocity));
}

std::array<Vec3, 4> nodal_forces(const Tetrahedron& tet, const SymTensor& stress) {
  std::array<Vec3, 4> forces;
  for (std::size_t n = 0; n < 4; ++n) forces[n] = stress.apply(tet.area[n]) / 3.0;
  return forces;
}

double largest_face_area(const Tetrahedron& tet) {
  double largest = 0.0;
  for (const Vec3& a : tet.area) largest = std::max(largest, a.norm());
  return largest;
}

}  // namespace dfc::fdm
