#pragma once
// Test support: a cavity mesh (dfc/continuum/cavity_meshes.hpp) whose wall is
// moved radially at a constant rate, the in-situ pressure held on the outer
// boundary, the wall pressure read from the reaction.
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "dfc/continuum/axisymmetric_solver.hpp"
#include "dfc/continuum/cavity_meshes.hpp"

namespace dfc::continuum::test {

enum class CavityShape { cylindrical, spherical };

/// The spherical cavity's meridian mesh of the tests: a₀ = 1 m, b = 20 a₀, 30
/// radial divisions graded by 1.1, 12 along the quarter circle: 720
/// triangles, those at the cavity about 0.12 a₀ × 0.13 a₀.
inline CavityMeshSpec spherical_test_mesh() {
  CavityMeshSpec spec;
  spec.inner_radius = 1.0;
  spec.outer_radius = 20.0;
  spec.radial_divisions = 30;
  spec.radial_ratio = 1.1;
  spec.tangential_divisions = 12;
  return spec;
}

/// The cylindrical cavity's strip mesh of the tests: a₀ = 1 m, b = 100 a₀,
/// 60 radial divisions graded by 1.075 (the first ring 0.1 a₀ wide), one
/// layer 0.1 a₀ high: 120 triangles.
inline CavityMeshSpec cylindrical_test_mesh() {
  CavityMeshSpec spec;
  spec.inner_radius = 1.0;
  spec.outer_radius = 100.0;
  spec.radial_divisions = 60;
  spec.radial_ratio = 1.075;
  spec.tangential_divisions = 1;
  spec.strip_height = 0.1;
  return spec;
}

/// Cylindrical: `strip_mesh`, plane strain (both faces on rollers).
/// Spherical: `quarter_annulus_mesh`, rollers on the equator and the axis.
class CavityExpansion {
 public:
  CavityExpansion(CavityShape shape, const CavityMeshSpec& spec, std::shared_ptr<const constitutive::ConstitutiveModel> model,
                  double in_situ_pressure, const SolverSettings& settings)
      : spherical_(shape == CavityShape::spherical),
        initial_radius_(spec.inner_radius),
        solver_(spherical_ ? quarter_annulus_mesh(spec) : strip_mesh(spec), std::move(model),
                Stress::isotropic(-in_situ_pressure), settings) {
    const AxisymmetricMesh& mesh = solver_.mesh();
    if (spherical_) {
      solver_.prescribe_velocity(mesh.node_group("equator"), Axis::z, 0.0);
      solver_.prescribe_velocity(mesh.node_group("axis"), Axis::r, 0.0);
    } else {
      solver_.prescribe_velocity(mesh.node_group("bottom"), Axis::z, 0.0);
      solver_.prescribe_velocity(mesh.node_group("top"), Axis::z, 0.0);
    }
    solver_.apply_pressure("outer", in_situ_pressure);
  }

  /// Moves the wall to a/a₀ = `ratio` in `steps` steps, calling `at_step` after each.
  template <typename Callback>
  void expand_to(double ratio, Index steps, Callback&& at_step) {
    move_wall((ratio * initial_radius_ - wall_radius()) / double(steps));
    for (Index s = 0; s < steps; ++s) {
      solver_.step();
      at_step();
    }
    move_wall(0.0);
  }
  void expand_to(double ratio, Index steps) {
    expand_to(ratio, steps, [] {});
  }
  /// Steps with the wall held.
  void settle(Index steps) {
    for (Index s = 0; s < steps; ++s) solver_.step();
  }

  [[nodiscard]] double radius_ratio() const { return wall_radius() / initial_radius_; }
  /// The wall's normal reaction over its area (hemisphere 2πa², cylinder 2πa h), Pa.
  [[nodiscard]] double wall_pressure() const { return wall_force() / wall_area(); }
  /// The wall's normal reaction, N.
  [[nodiscard]] double wall_force() const {
    double force = 0.0;
    for (const Index n : solver_.mesh().node_group("inner")) {
      const Index node[] = {n};
      force += solver_.internal_force_sum(node).dot(outward(n));
    }
    return force;
  }
  [[nodiscard]] AxisymmetricSolver& solver() { return solver_; }

 private:
  /// The wall moves radially: from the axis (cylinder) or the centre (sphere).
  [[nodiscard]] Point outward(Index node) const {
    return spherical_ ? Point(solver_.mesh().nodes[node].normalized()) : Point(1.0, 0.0);
  }
  [[nodiscard]] double wall_radius() const {
    const Point& p = solver_.mesh().nodes[solver_.mesh().node_group("inner").front()];
    return spherical_ ? p.norm() : p.x();
  }
  [[nodiscard]] double wall_area() const {
    const AxisymmetricMesh& mesh = solver_.mesh();
    const std::vector<Index>& wall = mesh.node_group("inner");
    const double a = wall_radius();
    const double height = mesh.nodes[wall.back()].y() - mesh.nodes[wall.front()].y();
    return 2.0 * std::numbers::pi * a * (spherical_ ? a : height);
  }
  void move_wall(double speed) {
    for (const Index n : solver_.mesh().node_group("inner")) {
      const Index node[] = {n};
      const Point direction = outward(n);
      solver_.prescribe_velocity(node, Axis::r, speed * direction.x());
      solver_.prescribe_velocity(node, Axis::z, speed * direction.y());
    }
  }

  bool spherical_;
  double initial_radius_;
  AxisymmetricSolver solver_;
};

struct Loading {
  Index expansion_steps = 0;        ///< steps to move the wall from a₀ to the last checkpoint
  Index settling_steps = 0;         ///< steps with the wall held at the end, before the last reading
  std::vector<double> checkpoints;  ///< a/a₀ where the pressure is read (the last one after settling)
};

struct CavityRun {
  std::vector<double> radius_ratios;  ///< a/a₀ at the checkpoints
  std::vector<double> pressures;      ///< Pa, compression positive
  std::vector<double> unbalanced;     ///< unbalanced-force ratio at the checkpoints
  double smallest_area_ratio = 0.0;
};

inline CavityRun expand_cavity(CavityShape shape, const CavityMeshSpec& spec,
                               std::shared_ptr<const constitutive::ConstitutiveModel> model, double in_situ_pressure,
                               const SolverSettings& settings, const Loading& loading) {
  CavityExpansion cavity(shape, spec, std::move(model), in_situ_pressure, settings);
  CavityRun run;
  const auto read = [&] {
    run.radius_ratios.push_back(cavity.radius_ratio());
    run.pressures.push_back(cavity.wall_pressure());
    run.unbalanced.push_back(cavity.solver().unbalanced_force_ratio());
  };
  std::size_t next = 0;
  cavity.expand_to(loading.checkpoints.back(), loading.expansion_steps, [&] {
    if (next + 1 < loading.checkpoints.size() && cavity.radius_ratio() >= loading.checkpoints[next] - 1e-12) {
      read();
      ++next;
    }
  });
  cavity.settle(loading.settling_steps);
  read();
  run.smallest_area_ratio = cavity.solver().smallest_area_ratio();
  return run;
}

}  // namespace dfc::continuum::test
