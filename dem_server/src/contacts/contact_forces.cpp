// Step 2 of the cycle: the only place the contact kernels are instantiated.
// std::visit picks the law once per step and list; the loops inside are
// compiled per law, with the law's evaluate inlined.
#include <span>
#include <variant>

#include "dfc/dem/contact_kernels.hpp"
#include "dfc/dem/particle_loads.hpp"
#include "dfc/dem/simulation.hpp"
#include "dfc/dem/wall_contacts.hpp"

namespace dfc::dem {

void Simulation::compute_pair_constants() {
  std::visit([&](const auto& table) { dfc::dem::compute_pair_constants(pair_laws(table, pairs_), particles_, pairs_, threads_); }, materials_.pair_laws());
}

bool Simulation::compute_contact_forces(double dt, ContactRecord record) {
  start_particle_loads(particles_, settings_.gravity, threads_);
  bool excessive = std::visit([&](const auto& table) {
    const auto laws = pair_laws(table, pairs_);
    const double limit = settings_.max_overlap_fraction;
    if (cell_) return evaluate_pair_contacts(laws, particles_, pairs_, incidence_, outputs_, dt, record, limit, threads_, PeriodicSpace(*cell_));
    return evaluate_pair_contacts(laws, particles_, pairs_, incidence_, outputs_, dt, record, limit, threads_);
  }, materials_.pair_laws());
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const std::size_t offset = wall_offsets_[w];
    select_wall_contacts(walls_[w], particles_, wall_contacts_[w], std::span(outputs_.point).subspan(offset, wall_contacts_[w].size()), threads_);
    excessive = std::visit([&](const auto& law) {
      return evaluate_wall_contacts(law, particles_, walls_[w], wall_contacts_[w], outputs_, offset, dt, settings_.max_overlap_fraction, threads_);
    }, walls_[w].law.law) || excessive;
  }
  return excessive;
}

}  // namespace dfc::dem
