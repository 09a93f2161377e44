#pragma once
// CoupledRun: the coupler's job from a validated scenario to a results file
// (docs/theory/coupling.md, docs/outputs.md):
//   1. start the participants and greet them (versions, capabilities),
//   2. configure each with its section (scenario hash checked),
//   3. exchange the interface mesh (continuum -> dem),
//   4. choose time steps: k DEM steps per exchange, m continuum steps covering the same time,
//   5. run the exchanges through a coupling scheme (coupling_scheme.hpp; serial: DEM, then
//      continuum, checking the force balance each time),
//   6. write time series and snapshots (HDF5 + XDMF), report progress and a summary;
//      every run.checkpoint_every exchanges and on a stop by signal, a coordinated
//      checkpoint (run_checkpoint.hpp) from which `run --resume` continues bit for bit.
#include <atomic>
#include <filesystem>
#include <iosfwd>
#include <memory>
#include <vector>

#include "dfc/coupler/participant.hpp"
#include "dfc/coupler/scenario.hpp"

namespace dfc::coupler {

struct RunOptions {
  std::filesystem::path output_directory;  ///< overrides the scenario's output.directory when not empty
  bool progress = true;
  const std::atomic<bool>* stop_requested = nullptr;  ///< set by SIGINT/SIGTERM: stop after the current exchange (and a checkpoint)
  /// Continue the run in output_directory from its last checkpoint (docs/checkpoints.md).
  bool resume = false;
};

/// Runs the scenario; progress and the summary go to `log`, failures to
/// `error_log`. Returns the process exit status: 0 success, 1 a participant
/// failed (message printed), 130 stopped by a signal. Throws
/// dfc::ConfigError / dfc::UserError for bad input found before the first step.
int run_scenario(const Scenario& scenario, const RunOptions& options, std::ostream& log, std::ostream& error_log);

/// `coupler check`: validates the scenario and every participant's section by
/// starting each server and configuring it (no step is run). Throws
/// dfc::ConfigError / dfc::UserError / ParticipantFailure.
void check_scenario(const Scenario& scenario, std::ostream& log);

}  // namespace dfc::coupler
