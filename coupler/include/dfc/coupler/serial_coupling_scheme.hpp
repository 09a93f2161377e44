#pragma once
// SerialCouplingScheme: the serial (staggered) coupling scheme of SPEC.md §5.3
// and docs/theory/coupling.md, the CouplingScheme (coupling_scheme.hpp) the
// coupler runs today.
#include <chrono>
#include <cstdint>
#include <utility>
#include <vector>

#include "dfc/coupler/coupling_scheme.hpp"
#include "dfc/protocol/message.hpp"

namespace dfc::coupler {

/// The serial (staggered) scheme, SPEC.md §5.3: each exchange the DEM
/// advances first, with the wall velocity from the continuum's last advance,
/// then the continuum, with the interface forces the DEM returned. A run with
/// one participant is the degenerate case: that participant advances alone.
class SerialCouplingScheme final : public CouplingScheme {
 public:
  /// `dem`, `continuum`: either may be null (an uncoupled run), not both;
  /// they, and `stop`, must outlive the scheme. `interface_nodes`: nodes of the
  /// interface mesh (0 when uncoupled). `force_balance_tolerance`: relative
  /// (coupling.force_balance_tolerance).
  SerialCouplingScheme(Participant* dem, Participant* continuum, const ExchangeTiming& timing, std::int64_t interface_nodes,
                       double force_balance_tolerance, std::chrono::milliseconds deadline, StopRequest& stop);

  ExchangeResult advance() override;
  [[nodiscard]] double time() const override;
  [[nodiscard]] CouplingState export_state() const override { return state_; }
  void import_state(CouplingState state) override { state_ = std::move(state); }

 private:
  [[nodiscard]] bool coupled() const { return dem_ != nullptr && continuum_ != nullptr; }
  /// The wall velocity to send the DEM, moving the coupler's wall record with it.
  std::vector<double> corrected_wall_velocity();
  void advance_dem(ExchangeResult& result, std::vector<protocol::Array>& to_continuum);
  void advance_continuum(ExchangeResult& result, std::vector<protocol::Array> from_dem);
  void check_force_balance(ExchangeResult& result);

  Participant* dem_;
  Participant* continuum_;
  ExchangeTiming timing_;
  std::int64_t nodes_;
  double tolerance_;
  std::chrono::milliseconds deadline_;
  StopRequest& stop_;
  CouplingState state_;
};

}  // namespace dfc::coupler
