// FdmBackend's checkpoint (protocol/SPEC.md §4.7, docs/checkpoints.md): the
// solver's running state (Solver::save_state) and the interface monitors of
// the last advance. The interface rows (which gridpoint each node is) follow
// from the section and set_interface, which a resumed run sends again first.
#include "dfc/fdm/stored_as_bytes.hpp"
#include "dfc/fdm/fdm_backend.hpp"

namespace dfc::fdm {

namespace {
constexpr std::uint32_t kLayoutVersion = 2;  ///< raise when the stored members change
}  // namespace

std::string FdmBackend::checkpoint_state() {
  StateWriter out;
  out.value(kLayoutVersion);
  solver().save_state(out);
  out.tag("interface monitors");
  out.value(interface_force_sum_);
  out.value(interface_power_);
  return out.take();
}

void FdmBackend::restore_state(std::string_view bytes) {
  StateReader in(bytes, "the fdm_server checkpoint");
  if (in.value<std::uint32_t>() != kLayoutVersion) in.fail("state layout " + std::to_string(kLayoutVersion));
  solver().load_state(in);
  in.tag("interface monitors");
  in.value(interface_force_sum_);
  in.value(interface_power_);
  in.finish();
}

}  // namespace dfc::fdm
