// Simulation::describe_largest_overlap: which contact broke the overlap guard
// (SimulationSettings::max_overlap_fraction). Runs only on the failure path,
// after compute_contact_forces reported an excessive overlap and before the
// particles move, so it sees the positions that step's forces came from.
#include <iomanip>
#include <sstream>

#include "dfc/dem/bond_state.hpp"
#include "dfc/dem/periodic_cell.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {
namespace {

const char* bond_state_name(BondState s) noexcept {
  switch (s) {
    case BondState::none: return "never bonded";
    case BondState::intact: return "bond intact";
    case BondState::damaged: return "bond damaged";
    case BondState::broken_tension: return "bond broken in tension";
    case BondState::broken_shear: return "bond broken in shear";
  }
  return "unknown bond state";
}

void describe_particle(std::ostream& out, const ParticleStore& p, std::size_t i) {
  const Vec3 x = p.position[i];
  const Vec3 v = p.velocity[i];
  out << "particle id " << p.id[i] << " (radius " << p.radius[i] << " m, at [" << x.x << ", " << x.y << ", " << x.z << "] m, speed " << norm(v)
      << " m/s)";
}

}  // namespace

std::string Simulation::describe_largest_overlap() const {
  const PeriodicSpace space = cell_ ? PeriodicSpace(*cell_) : PeriodicSpace();
  const bool bonded = settings_.particle_law.bonded() && pairs_.stride > 0;
  // The largest overlap relative to the radius the guard compares it with.
  double worst = -1.0;
  std::ostringstream what;
  what << std::setprecision(4);
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const std::uint32_t i = pairs_.first[k], j = pairs_.second[k];
    const double ri = particles_.radius[i], rj = particles_.radius[j];
    const double overlap = ri + rj - norm(space.branch(particles_.position[i], particles_.position[j]));
    const double ratio = overlap / std::min(ri, rj);
    if (!(ratio > worst)) continue;
    worst = ratio;
    what.str("");
    what << "the pair of ";
    describe_particle(what, particles_, i);
    what << " and ";
    describe_particle(what, particles_, j);
    what << ": overlap " << overlap << " m = " << ratio << " of the smaller radius";
    if (bonded) what << ", " << bond_state_name(bond_state(pairs_.history.data() + k * pairs_.stride));
  }
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const WallContacts& contacts = wall_contacts_[w];
    for (std::size_t c = 0; c < contacts.size(); ++c) {
      if (contacts.selected[c] == 0) continue;
      const std::uint32_t i = contacts.particle[c];
      const double overlap = particles_.radius[i] - contacts.distance[c];
      const double ratio = overlap / particles_.radius[i];
      if (!(ratio > worst)) continue;
      worst = ratio;
      what.str("");
      what << "wall '" << walls_[w].name << "' and ";
      describe_particle(what, particles_, i);
      what << ": overlap " << overlap << " m = " << ratio << " of its radius";
    }
  }
  return worst < 0.0 ? std::string("no overlapping contact found") : "the largest is " + what.str();
}

}  // namespace dfc::dem
