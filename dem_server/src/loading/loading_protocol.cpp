#include "dfc/dem/loading_protocol.hpp"

#include <array>

#include "dfc/dem/dem_config.hpp"

namespace dfc::dem {

std::span<const LoadingProtocolEntry> loading_protocol_registry() {
  // Preparation stages first (cell consolidation, confinement in walls; the
  // section reader refuses both at once), then the protocols that take
  // their references from the prepared model.
  static constexpr std::array<LoadingProtocolEntry, 4> registry{{
      {"periodic", &make_cell_loading, &declare_cell_monitors},
      {"triaxial", &make_triaxial_loading, &declare_triaxial_monitors},
      {"ucs", &make_ucs_loading, &declare_ucs_monitors},
      {"pile", &make_pile_loading, &declare_pile_monitors},
  }};
  return registry;
}

std::vector<std::unique_ptr<LoadingProtocol>> make_loading_protocols(const DemConfig& config) {
  std::vector<std::unique_ptr<LoadingProtocol>> protocols;
  for (const LoadingProtocolEntry& entry : loading_protocol_registry())
    if (auto protocol = entry.make(config)) protocols.push_back(std::move(protocol));
  return protocols;
}

}  // namespace dfc::dem
