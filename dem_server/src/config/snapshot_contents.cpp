#include "dfc/dem/snapshot_contents.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace dfc::dem {

SnapshotContents read_snapshot_contents(ConfigReader& dem_section) {
  SnapshotContents c;
  auto block = dem_section.optional_child("snapshot");
  if (!block) return c;
  // The declaration's choices have checked every entry (an unknown one is a
  // ConfigError naming it and listing the choices).
  const std::vector<std::string> contents = block->strings("contents");
  const auto has = [&](const char* entry) { return std::find(contents.begin(), contents.end(), entry) != contents.end(); };
  c.particle_stress = has("particle_stress");
  c.bonds = has("bonds");
  c.contacts = has("contacts");
  c.walls = has("walls");
  c.contacts_min_force = block->number("contacts_min_force_n");
  block->finish();
  return c;
}

}  // namespace dfc::dem
