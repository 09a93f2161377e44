#pragma once
// Coordinated checkpoints of a coupled run (docs/checkpoints.md, SPEC.md §4.7).
//
// A run's checkpoint is the folder DIR/checkpoint/ next to DIR/results.h5:
//   <slot>.checkpoint   each server's complete state (written by the server)
//   coupler.checkpoint  the coupler's: the loop state, where the results file
//                       stood, the scenario and the solvers' versions
// It is written at an exchange boundary into DIR/checkpoint.partial/ and then
// renamed into place (the previous one kept as checkpoint.previous until the
// rename is done), so a process killed at any moment leaves one complete
// checkpoint, never a mixture of two.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "dfc/coupler/coupling_scheme.hpp"
#include "dfc/coupler/participant.hpp"
#include "dfc/coupler/scenario.hpp"

namespace dfc::coupler {

/// What the coupling loop carries from one exchange to the next: all of it is
/// in a checkpoint, so a resumed loop continues bit for bit.
struct LoopState {
  CouplingState coupling;  ///< the coupling scheme's (coupling_scheme.hpp): exchange index, steps, interface kinematics, force balance
  double wall_time_s = 0.0;  ///< s, wall time the exchanges done took (across resumed processes)
  std::map<std::string, nlohmann::json> monitors;  ///< per slot, of the last exchange
};

/// The coupler's part of a checkpoint.
struct CouplerCheckpoint {
  nlohmann::json scenario;  ///< the scenario document the run started with
  nlohmann::json solvers;   ///< per slot: {name, version} from hello
  nlohmann::json results;   ///< ResultsWriter::resume_point()
  nlohmann::json recorder;  ///< the time-series columns' sources
  LoopState loop;
};

class RunCheckpoints {
 public:
  explicit RunCheckpoints(std::filesystem::path run_directory);

  /// Every participant writes its state, then the coupler its own; then the
  /// new checkpoint replaces the last. Throws ParticipantFailure naming the server that failed.
  void write(std::vector<std::unique_ptr<Participant>>& participants, const CouplerCheckpoint& state,
             std::chrono::milliseconds deadline) const;
  /// The last complete checkpoint. Throws UserError when there is none or it cannot be read.
  [[nodiscard]] CouplerCheckpoint read() const;
  /// Throws UserError naming what differs when the checkpoint cannot continue
  /// `scenario` with these participants (another scenario, solver or version).
  static void check_resumable(const CouplerCheckpoint& checkpoint, const Scenario& scenario,
                              const std::vector<std::unique_ptr<Participant>>& participants);
  /// Each participant (configured, interface set) restores its state; checks
  /// the steps they report against the coupler's.
  void restore(std::vector<std::unique_ptr<Participant>>& participants, const LoopState& loop, std::chrono::milliseconds deadline) const;
  /// The folder holding the last complete checkpoint (checkpoint/, or checkpoint.previous/ after a kill between the renames).
  [[nodiscard]] std::filesystem::path committed() const;

 private:
  std::filesystem::path directory_;
};

}  // namespace dfc::coupler
