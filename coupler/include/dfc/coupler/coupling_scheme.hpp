#pragma once
// CouplingScheme: how the participants of a run advance together, one
// exchange at a time (docs/theory/coupling.md). run_scenario (coupled_run.cpp)
// orchestrates — start, results, snapshots, checkpoints, stop conditions,
// progress, summary — and asks the scheme for one exchange after another; the
// scheme owns what couples the solvers: the order of their advances, the
// interface kinematics and the interface force-balance check.
//
// Everything a scheme carries from one exchange to the next is its
// CouplingState: export_state() hands it to a checkpoint, import_state()
// takes it back on a resume, so a resumed run continues bit for bit.
//
//   SerialCouplingScheme scheme(dem, continuum, timing, n_nodes, tolerance, deadline, stop);  // serial_coupling_scheme.hpp
//   if (resumed) scheme.import_state(checkpoint.loop.coupling);
//   while (...) { const ExchangeResult r = scheme.advance(); ... }
//   checkpoint.loop.coupling = scheme.export_state();
#include <array>
#include <chrono>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/coupler/participant.hpp"

namespace dfc::coupler {

/// Time steps of the run (SPEC.md §5.3): exchange duration T = k·dt_dem = m·dt_continuum.
struct ExchangeTiming {
  std::int64_t dem_steps_per_exchange = 0;
  std::int64_t continuum_steps_per_exchange = 0;
  double dt_dem = 0.0;
  double dt_continuum = 0.0;
  [[nodiscard]] double exchange_duration() const {
    return dem_steps_per_exchange > 0 ? double(dem_steps_per_exchange) * dt_dem : double(continuum_steps_per_exchange) * dt_continuum;
  }
};

/// What a coupling scheme carries between exchanges: all of it goes into a
/// checkpoint (run_checkpoint.hpp).
struct CouplingState {
  std::int64_t exchanges_done = 0;
  std::int64_t dem_step = 0;
  std::int64_t continuum_step = 0;
  /// Interface kinematics: the continuum's last velocity and displacement,
  /// and where the coupler has moved the DEM's wall (n_nodes × 3 each).
  std::vector<double> velocity, continuum_displacement, wall_displacement;
  /// Force-balance bookkeeping: the worst relative mismatch of the checked
  /// exchanges; the exchanges at which a side sent no interface force
  /// monitor (SPEC.md §6.3 names them, but a server may omit them), and why.
  double worst_balance = 0.0;
  std::int64_t unchecked_balances = 0;
  std::string missing_balance_monitors;
};

/// What one exchange produced.
struct ExchangeResult {
  std::int64_t exchange = 0;  ///< 0-based index of the exchange just done
  double time_s = 0.0;        ///< s, model time at its end
  std::int64_t dem_step = 0;
  std::int64_t continuum_step = 0;
  /// The monitors each participant sent with its advance, by slot.
  std::map<std::string, nlohmann::json> monitors;
  /// N, the interface force on each side (NaN where not known: an uncoupled
  /// run, or a side that sent no interface force monitor).
  static constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  std::array<double, 3> force_on_dem{kUnknown, kUnknown, kUnknown};
  std::array<double, 3> force_on_continuum{kUnknown, kUnknown, kUnknown};
};

class CouplingScheme {
 public:
  virtual ~CouplingScheme() = default;
  /// Advances every participant by one exchange. Throws ParticipantFailure
  /// (a server failed, or the interface forces did not balance) or RunInterrupted.
  virtual ExchangeResult advance() = 0;
  /// s, the model time the participants have reached.
  [[nodiscard]] virtual double time() const = 0;
  [[nodiscard]] virtual CouplingState export_state() const = 0;
  /// Continues from `state` (exported by a scheme of the same run).
  virtual void import_state(CouplingState state) = 0;
};

}  // namespace dfc::coupler
