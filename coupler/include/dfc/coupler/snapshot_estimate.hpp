#pragma once
// What a DEM snapshot will hold, array by array, estimated at configure time
// from the counts the DEM server reports and what the DEM section's
// "snapshot" block asks for (docs/looking_at_a_run.md §4): the coupler
// refuses, naming the scenario key to change, a model whose snapshot has an
// array over the protocol's limit per array (SPEC.md §8) or needs more
// memory than the machine has, before the run starts rather than at its
// first snapshot.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace dfc::coupler {

/// One array of a snapshot and what it will take.
struct SnapshotArrayEstimate {
  std::string name;    ///< the dataset (protocol/SPEC.md §6.4), e.g. "bond_position"
  double rows = 0.0;
  std::string rows_are;  ///< what a row is: "particles", "bonds", "contacts"
  double row_bytes = 0.0;
  std::string key;     ///< the scenario key that makes it smaller or leaves it out
  std::string remedy;  ///< how, in words
  [[nodiscard]] double bytes() const noexcept { return rows * row_bytes; }
};

/// Every array of a particle snapshot whose size depends on the model: the
/// four every snapshot has (particle_position, particle_radius,
/// particle_velocity, particle_id) and, as `dem_config`'s "snapshot" block
/// asks (its defaults without one: particle_stress, bonds, walls), the
/// particle stress, the bonds and the contacts. `monitors` are the server's
/// after configure: particle_count, the bonds_* counts (every bonded pair
/// stays in the snapshot once broken) and contact_count. Contacts, which grow
/// as the bed is loaded, count at least as the bonds and as a dense packing
/// (3 per particle, coordination number 6) unless contacts_min_force_n
/// leaves some out. `key` is the DEM section's key path ("participants.dem").
/// Empty without a particle_count.
[[nodiscard]] std::vector<SnapshotArrayEstimate> estimate_dem_snapshot(const nlohmann::json& dem_config, const nlohmann::json& monitors,
                                                                       const std::string& key);

/// Throws a ConfigError naming the array's key for the first array over
/// `array_limit` bytes (estimate_dem_snapshot lists the arrays every snapshot
/// has first, then each optional group largest first, so the key named is
/// one whose change helps), and for a snapshot that needs more than
/// `available_memory` bytes in the coupler (it holds a snapshot about three
/// times while receiving and writing it).
void check_snapshot_estimate(const std::vector<SnapshotArrayEstimate>& arrays, double array_limit, std::optional<double> available_memory);

}  // namespace dfc::coupler
