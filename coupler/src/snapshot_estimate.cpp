#include "dfc/coupler/snapshot_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dfc/common/errors.hpp"

namespace dfc::coupler {

namespace {

/// A monitor's value, 0 where the server does not report it (an unbonded law has no bonds_* monitors).
double count(const nlohmann::json& monitors, const char* name) {
  const auto it = monitors.find(name);
  return it != monitors.end() && it->is_number() ? std::max(0.0, it->get<double>()) : 0.0;
}

std::string gib(double bytes) {
  std::ostringstream text;
  text.precision(3);
  text << bytes / double(1ULL << 30) << " GiB";
  return text.str();
}

std::string whole(double value) { return std::to_string(static_cast<long long>(std::llround(value))); }

std::string two_digits(double value) {
  std::ostringstream text;
  text.precision(2);
  text << value;
  return text.str();
}

/// Contacts per particle of a dense packing of spheres (coordination number 6).
constexpr double kDenseContactsPerParticle = 3.0;

}  // namespace

std::vector<SnapshotArrayEstimate> estimate_dem_snapshot(const nlohmann::json& dem_config, const nlohmann::json& monitors, const std::string& key) {
  std::vector<SnapshotArrayEstimate> arrays;
  const auto particle_count = monitors.find("particle_count");
  if (particle_count == monitors.end() || !particle_count->is_number()) return arrays;
  const double particles = std::max(0.0, particle_count->get<double>());
  // The block's defaults are those of common/src/sections/dem_sections.cpp.
  std::vector<std::string> contents{"particle_stress", "bonds", "walls"};
  double min_force = 0.0;
  if (const auto block = dem_config.find("snapshot"); block != dem_config.end() && block->is_object()) {
    if (const auto listed = block->find("contents"); listed != block->end() && listed->is_array()) contents = listed->get<std::vector<std::string>>();
    if (const auto f = block->find("contacts_min_force_n"); f != block->end() && f->is_number()) min_force = f->get<double>();
  }
  const auto has = [&](const char* entry) { return std::find(contents.begin(), contents.end(), entry) != contents.end(); };
  const std::string particles_key = key + ".config" + (dem_config.contains("particles") ? ".particles" : "");
  const std::string contents_key = key + ".config.snapshot.contents";
  const std::string fewer = "use fewer particles or larger ones";
  for (const auto& [name, row_bytes] : {std::pair{"particle_position", 24.0}, {"particle_radius", 8.0}, {"particle_velocity", 24.0}, {"particle_id", 8.0}})
    arrays.push_back({name, particles, "particles", row_bytes, particles_key, fewer});
  if (has("particle_stress"))
    arrays.push_back({"particle_stress_pa", particles, "particles", 48.0, contents_key, "leave \"particle_stress\" out of it, or " + fewer});
  const double bonds = count(monitors, "bonds_intact") + count(monitors, "bonds_damaged") + count(monitors, "bonds_broken_tension") +
                       count(monitors, "bonds_broken_shear");
  if (has("bonds") && bonds > 0.0) {
    const std::string remedy = "leave \"bonds\" out of it (" + two_digits(bonds / std::max(particles, 1.0)) + " bonds per particle), or " + fewer;
    for (const auto& [name, row_bytes] : {std::pair{"bond_position", 24.0}, {"bond_state", 8.0}, {"bond_particle_index", 16.0},
                                          {"bond_particle_id", 16.0}, {"bond_normal_force_n", 8.0}, {"bond_shear_force_n", 8.0},
                                          {"bond_opening_m", 8.0}})
      arrays.push_back({name, bonds, "bonds", row_bytes, contents_key, remedy});
  }
  if (has("contacts")) {
    // How many contacts reach a positive contacts_min_force_n is not known
    // before the run: then only those the server counts now.
    double contacts = count(monitors, "contact_count");
    if (min_force <= 0.0) contacts = std::max({contacts, bonds, kDenseContactsPerParticle * particles});
    const std::string rows_are = min_force <= 0.0 ? "contacts to expect (its bonds, a dense packing's 3 per particle, or those it has now)" : "contacts";
    const std::string remedy = "raise it to leave the small contacts out, leave \"contacts\" out of " + contents_key + ", or " + fewer;
    for (const auto& [name, row_bytes] : {std::pair{"contact_force_n", 24.0}, {"contact_particle_index", 16.0}, {"contact_normal_force_n", 8.0}})
      arrays.push_back({name, contacts, rows_are, row_bytes, key + ".config.snapshot.contacts_min_force_n", remedy});
  }
  return arrays;
}

void check_snapshot_estimate(const std::vector<SnapshotArrayEstimate>& arrays, double array_limit, std::optional<double> available_memory) {
  if (arrays.empty()) return;
  const auto over = std::find_if(arrays.begin(), arrays.end(), [&](const auto& a) { return a.bytes() > array_limit; });
  if (over != arrays.end())
    throw ConfigError(over->key, "the model has " + whole(over->rows) + " " + over->rows_are + "; their " + over->name + " in a snapshot would take " +
                                     gib(over->bytes()) + ", over the protocol's " + gib(array_limit) + " per array (SPEC.md §8): " + over->remedy);
  // While a snapshot is received the coupler holds it twice (the frames and
  // the decoded arrays) and the HDF5 writer a third time.
  double snapshot = 0.0;
  for (const auto& a : arrays) snapshot += a.bytes();
  const double needed = 3.0 * snapshot;
  if (available_memory && needed > *available_memory)
    throw ConfigError(arrays.front().key, "the model has " + whole(arrays.front().rows) + " particles; taking a snapshot of them (" + gib(snapshot) +
                                              ") needs about " + gib(needed) + " in the coupler but this machine has " + gib(*available_memory) +
                                              " available: use fewer particles or larger ones, leave arrays out of the DEM section's "
                                              "snapshot.contents, or use a machine with more memory");
}

}  // namespace dfc::coupler
