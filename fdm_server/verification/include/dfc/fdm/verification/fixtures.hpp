#pragma once
// Building blocks the verification problems share: solver settings, loading
// and equilibrium, plane-strain and spherical fixtures, stress components in
// polar coordinates, and small fitting helpers.
#include <array>
#include <chrono>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dfc/fdm/mesh_generators.hpp"
#include "dfc/fdm/solver.hpp"

namespace dfc::fdm::verification {

/// Wall-clock seconds since construction.
class Stopwatch {
 public:
  [[nodiscard]] double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

/// Quasi-static settings (§1.9, §1.10): local damping 0.8, mass scaling, one
/// thread (the test budget is per core; results do not depend on it).
[[nodiscard]] SolverSettings static_settings();

/// The equilibrium every static problem is compared at: average unbalanced-force
/// ratio 1e-6, ten times below FLAC's default 1e-5, so that the convergence
/// error is well below the tolerances.
inline constexpr double kEquilibriumRatio = 1e-6;

/// Steps to `target_ratio` (dt = 1, mass scaling); throws dfc::SolverError
/// naming `problem` if it does not converge. Returns the steps taken.
int equilibrate(Solver& solver, std::string_view problem, double target_ratio = kEquilibriumRatio);

/// Ramps the external forces linearly from `from` to `to` over `steps` steps
/// (dt = 1): plastic problems are loaded quasi-statically, so that the inertial
/// overshoot of a sudden load cannot yield zones the static path would not.
void ramp_external_forces(Solver& solver, std::span<const Vec3> from, std::span<const Vec3> to, int steps);

/// Applies the external forces from `from` to `to` in `stages` equal
/// increments, each held until the unbalanced-force ratio is below
/// `stage_ratio`: a static load path for plastic problems, independent of the
/// inertia of the mass-scaled relaxation. Returns the steps taken.
int load_in_stages(Solver& solver, std::span<const Vec3> from, std::span<const Vec3> to, int stages, std::string_view problem,
                   double stage_ratio = 1e-5);

/// Lumped nodal forces (one per gridpoint) of a uniform pressure (> 0 pushes
/// into the body) on a face group, as the "pressure" boundary condition applies them.
[[nodiscard]] std::vector<Vec3> pressure_forces(const Mesh& mesh, std::string_view group, double pressure);

/// Lumped nodal forces of the traction σ(x)·n of a stress field on a face group:
/// each quad gives σ(c)·a/4 to each corner (c its centroid, a its outward vector area).
[[nodiscard]] std::vector<Vec3> stress_field_forces(const Mesh& mesh, std::string_view group,
                                                    const std::function<Stress(const Vec3&)>& stress_at);

/// Cylindrical components about the z axis at x (tension positive).
struct CylindricalStress {
  double rr = 0.0, tt = 0.0, rt = 0.0;
};
[[nodiscard]] CylindricalStress cylindrical_components(const Stress& stress, const Vec3& x);

/// Spherical components about the origin at x: σ_rr and the mean of the two
/// tangential normal stresses (equal in a spherically symmetric field).
struct SphericalStress {
  double rr = 0.0, tt = 0.0;
};
[[nodiscard]] SphericalStress spherical_components(const Stress& stress, const Vec3& x);

/// A plane-strain quarter annulus a <= r <= b, 0 <= θ <= 90°, one zone thick,
/// with z rollers (plane strain) and symmetry rollers on θ = 0 (y = 0) and
/// θ = 90° (x = 0). The radial spacing is log-polar, Δr ∝ r (grading
/// (b/a)^(1/n_r)), so zones are near-square at every radius.
struct QuarterAnnulus {
  double inner_radius = 1.0;
  double outer_radius = 5.0;
  Index zones_radial = 12;
  Index zones_around = 12;
};
[[nodiscard]] CylinderCavitySpec quarter_annulus_spec(const QuarterAnnulus& annulus);
[[nodiscard]] Solver make_quarter_annulus(const QuarterAnnulus& annulus, Material material);

/// Volume-weighted averages over the zones of one radial layer (ring of the
/// annulus, shell of the sphere octant: both meshes number zones radial index
/// fastest) of the stress in polar components, at the layer's mean centroid radius.
struct LayerStress {
  double radius = 0.0;  ///< mean centroid distance from the z axis (cylindrical) or the origin (spherical), m
  double rr = 0.0;      ///< σ_rr, Pa, tension positive
  double tt = 0.0;      ///< σ_θθ (spherical: mean tangential), Pa
  double zz = 0.0;      ///< σ_zz (cylindrical only), Pa
};
[[nodiscard]] std::vector<LayerStress> radial_layers(const Solver& solver, Index zones_radial, bool spherical);

/// Mean outward radial displacement (about the z axis) of a face group's gridpoints.
[[nodiscard]] double mean_radial_displacement(const Solver& solver, std::string_view group, bool spherical = false);

/// y at x on the line through (x1, y1) and (x2, y2).
[[nodiscard]] double extrapolate_linear(double x, double x1, double y1, double x2, double y2);

/// y at x on the parabola through three points (Lagrange form).
[[nodiscard]] double extrapolate_quadratic(double x, const std::array<double, 3>& xs, const std::array<double, 3>& ys);

/// Least-squares line y = intercept + slope·x.
struct LineFit {
  double intercept = 0.0;
  double slope = 0.0;
};
[[nodiscard]] LineFit fit_line(std::span<const double> x, std::span<const double> y);

/// `value` with `decimals` digits after the point (labels of the rows).
[[nodiscard]] std::string format_fixed(double value, int decimals);

/// "n1×n2×n3" with the zone count, for the mesh column.
[[nodiscard]] std::string lattice_text(std::string_view kind, Index n1, Index n2, Index n3, std::size_t zones);

}  // namespace dfc::fdm::verification
