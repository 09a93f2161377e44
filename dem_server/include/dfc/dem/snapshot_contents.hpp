#pragma once
// What a particle snapshot holds beyond the arrays protocol/SPEC.md §6.4
// requires (position, radius, velocity, id): the DEM section's "snapshot"
// block (common/src/sections/dem_sections.cpp declares its keys;
// docs/looking_at_a_run.md §4 says what each costs). Particle materials and
// the pcrm profiles are written whenever the body has them: they are small.
#include "dfc/common/config_reader.hpp"

namespace dfc::dem {

struct SnapshotContents {
  bool particle_stress = true;  ///< particle_stress_pa
  bool bonds = true;            ///< the bond_* lines (bonded laws only; snapshot_pairs.hpp)
  bool contacts = false;        ///< the contact_* lines (snapshot_pairs.hpp)
  bool walls = true;            ///< wall_vertices, wall_facets, wall_facet_wall
  double contacts_min_force = 0.0;  ///< N, smallest |normal force| of a contact written
};

/// Reads the "snapshot" block; its defaults without one.
[[nodiscard]] SnapshotContents read_snapshot_contents(ConfigReader& dem_section);

}  // namespace dfc::dem
