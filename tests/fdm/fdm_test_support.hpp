#pragma once
// Shared set-up for the FDM tests: an elastic material and a run-to-equilibrium loop.
#include <memory>

#include <gtest/gtest.h>

#include "dfc/constitutive/elastic_model.hpp"
#include "dfc/fdm/equilibrium.hpp"
#include "dfc/fdm/hex_overlays.hpp"
#include "dfc/fdm/solver.hpp"

namespace dfc::fdm::test {

/// Volume of a mesh from one overlay of its tetrahedra (five fill a zone);
/// every tetrahedron of both overlays must have positive volume.
inline double mesh_volume(const Mesh& mesh) {
  double volume = 0.0;
  for (Index z = 0; z < mesh.zone_count(); ++z) {
    const auto tets = zone_tetrahedra(mesh, z);
    for (std::size_t t = 0; t < kTetrahedraPerZone; ++t) {
      EXPECT_GT(tets[t].volume, 0.0) << "zone " << z << " tetrahedron " << t;
      if (t < 5) volume += tets[t].volume;
    }
  }
  return volume;
}

inline Material elastic_material(double young_modulus, double poisson_ratio, double density) {
  return {density, std::make_unique<constitutive::ElasticModel>(constitutive::ElasticModel::from_young_poisson(young_modulus, poisson_ratio))};
}

/// Steps until the unbalanced-force ratio drops below `target` (after a few
/// steps, so that a load has been felt). Returns the steps taken, or -1.
inline int run_to_equilibrium(Solver& solver, double dt, double target, int max_steps) {
  return step_to_equilibrium(solver, EquilibriumSettings{dt, target, 10, max_steps});
}

inline SolverSettings quiet_settings(Vec3 gravity = Vec3::Zero()) {
  SolverSettings settings;
  settings.gravity = gravity;
  settings.threads = 1;  // the test machine is shared; results do not depend on it
  return settings;
}

}  // namespace dfc::fdm::test
