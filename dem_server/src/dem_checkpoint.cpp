// DemBackend's checkpoint (protocol/SPEC.md §4.7, docs/checkpoints.md): the
// simulation's running state (Simulation::save_state), the monitors the last
// advance averaged, and each loading protocol's running state
// (LoadingProtocol::save_state: whether the pile still waits for
// pile.start_when and the step it started at). Everything else (the servo and
// triaxial controls, the platen axis, the pile's and the cell's references,
// the generation report) follows from the section and the interface mesh,
// which a resumed run sends again before restore: it is rebuilt, not stored.
#include <string>

#include "dfc/common/state_archive.hpp"
#include "dfc/dem/dem_backend.hpp"

namespace dfc::dem {

namespace {
constexpr std::uint32_t kLayoutVersion = 6;  ///< raise when the stored members change
}  // namespace

std::string DemBackend::checkpoint_state() {
  StateWriter out;
  out.value(kLayoutVersion);
  // The whole body as one process holds it, gathered on rank 0 from a body
  // on many processes: any process count restores it (restore_state loads it
  // whole everywhere; the engine cuts it where its last rebuild saw it).
  engine().save_whole_body(out);
  out.tag("averages");
  out.string(averages_.dump());  // numbers as shortest round-trip text: the same doubles come back
  out.tag("loading");
  for (const auto& protocol : model_.loading) protocol->save_state(out);
  return out.take();
}

void DemBackend::restore_state(std::string_view bytes) {
  engine_.reset();  // the body is replaced: its engine is made again at the next use
  StateReader in(bytes, "the dem_server checkpoint");
  if (in.value<std::uint32_t>() != kLayoutVersion) in.fail("state layout " + std::to_string(kLayoutVersion));
  sim().load_state(in);
  in.tag("averages");
  const std::string averages = in.string();
  averages_ = nlohmann::json::parse(averages, nullptr, false);
  if (!averages_.is_object()) in.fail("the averaged monitors as a JSON object");
  in.tag("loading");
  for (const auto& protocol : model_.loading) protocol->load_state(in);
  in.finish();
}

}  // namespace dfc::dem
