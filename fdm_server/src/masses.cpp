#include "dfc/fdm/masses.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dfc/fdm/hex_overlays.hpp"

namespace dfc::fdm {

std::vector<double> lumped_masses(std::size_t gridpoint_count, std::span<const Tetrahedron> tetrahedra, double density) {
  std::vector<double> mass(gridpoint_count, 0.0);
  for (const Tetrahedron& tet : tetrahedra)
    for (const Index gp : tet.nodes) mass[gp] += kOverlayWeight * density * tet.volume / 4.0;
  return mass;
}

std::vector<double> mass_scaling_coefficients(std::size_t gridpoint_count, std::span<const Tetrahedron> tetrahedra,
                                              double p_wave_modulus) {
  std::vector<double> coefficient(gridpoint_count, 0.0);
  for (const Tetrahedron& tet : tetrahedra)
    for (std::size_t n = 0; n < 4; ++n) {
      const double largest_component = tet.area[n].cwiseAbs().maxCoeff();
      coefficient[tet.nodes[n]] += p_wave_modulus / (9.0 * tet.volume) * largest_component * largest_component;
    }
  return coefficient;
}

double critical_timestep(std::span<const Tetrahedron> tetrahedra, double p_wave_modulus, double density) {
  const double wave_speed = std::sqrt(p_wave_modulus / density);
  double smallest = std::numeric_limits<double>::infinity();
  for (const Tetrahedron& tet : tetrahedra) smallest = std::min(smallest, tet.volume / (wave_speed * largest_face_area(tet)));
  return 0.5 * smallest;
}

}  // namespace dfc::fdm
