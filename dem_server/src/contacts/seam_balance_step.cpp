// Simulation::balance_seams: the seam balance (seam_balance.hpp) on the
// simulation's own lists, at the step that follows bond_across_materials_now.
#include <algorithm>
#include <iostream>

#include "dfc/common/errors.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

void Simulation::balance_seams(double dt) {
  join_materials_requested_ = false;
  if (!settings_.particle_law.can_add_bond_load()) return;  // seam bonds keep the law's zero load
  if (compute_contact_forces(dt, ContactRecord::complete))
    throw SolverError("a contact overlap exceeded timestep.max_overlap_fraction of a particle radius before the seam balance (" + describe_largest_overlap() +
                      "): the generated body overlaps; check the zones' seam settings");

  // Every particle's out-of-balance force: contacts and weight; which ones a wall holds.
  std::vector<Vec3> residual(particles_.size());
  std::vector<bool> supported(particles_.size(), false);
  for (std::size_t i = 0; i < particles_.size(); ++i) residual[i] = particles_.mass[i] * settings_.gravity;
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    residual[pairs_.first[k]] += outputs_.force[k];
    residual[pairs_.second[k]] -= outputs_.force[k];
  }
  for (std::size_t w = 0; w < walls_.size(); ++w)
    for (std::size_t c = 0; c < wall_contacts_[w].size(); ++c) {
      const Vec3& f = outputs_.force[wall_offsets_[w] + c];
      residual[wall_contacts_[w].particle[c]] += f;
      if (f != Vec3{}) supported[wall_contacts_[w].particle[c]] = true;
    }

  // The band: bonds within seam_balance_hops of a seam bond's particles.
  std::vector<std::size_t> bonded;
  std::vector<BondEnds> ends;
  std::vector<bool> seam_particle(particles_.size(), false);
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    if (!is_bonded(bond_state(pairs_.row(k)))) continue;
    bonded.push_back(k);
    ends.push_back({pairs_.first[k], pairs_.second[k]});
    if (particles_.material[pairs_.first[k]] != particles_.material[pairs_.second[k]]) {
      seam_particle[pairs_.first[k]] = seam_particle[pairs_.second[k]] = true;
      ++seam_report_.seam_bonds;
    }
  }
  const std::vector<bool> band = within_bond_hops(particles_.size(), ends, seam_particle, seam_balance_hops);
  std::vector<std::size_t> band_pairs;
  std::vector<BondEnds> band_ends;
  std::vector<double> conductance;
  for (std::size_t b = 0; b < bonded.size(); ++b)
    if (band[ends[b][0]] && band[ends[b][1]]) {
      band_pairs.push_back(bonded[b]), band_ends.push_back(ends[b]);
      conductance.push_back(particles_.material[ends[b][0]] != particles_.material[ends[b][1]] ? seam_bond_conductance : 1.0);
    }
  const BondNetworkBalance balance = balance_bond_network(particles_.size(), band_ends, conductance, residual, supported);

  // Each correction onto its bond through the pair law's stiffness.
  const PeriodicSpace space = cell_ ? PeriodicSpace(*cell_) : PeriodicSpace();
  for (std::size_t b = 0; b < band_pairs.size(); ++b) {
    const std::size_t k = band_pairs[b];
    const std::uint32_t i = pairs_.first[k], j = pairs_.second[k];
    const Vec3 branch = space.branch(particles_.position[i], particles_.position[j]);
    const double distance = norm(branch);
    ContactKinematics kin;
    kin.normal = (1.0 / distance) * branch;
    kin.overlap = particles_.radius[i] + particles_.radius[j] - distance;
    kin.radius_first = particles_.radius[i];
    kin.radius_second = particles_.radius[j];
    kin.effective_mass = particles_.mass[i] * particles_.mass[j] / (particles_.mass[i] + particles_.mass[j]);
    kin.dt = dt;
    const ContactLawSetting& law = pairs_.law_index.empty() ? settings_.particle_law : materials_.pair_setting(pairs_.law_index[k]);
    law.add_bond_load(pairs_.row(k), kin, balance.correction[b]);
  }
  seam_report_.band_bonds = band_pairs.size();
  seam_report_.band_particles = std::size_t(std::count(band.begin(), band.end(), true));
  seam_report_.iterations = balance.iterations;
  seam_report_.residual_before = balance.residual_before;
  seam_report_.residual_after = balance.residual_after;
  std::cerr << "dem_server: seam balance: " << seam_report_.seam_bonds << " seam bonds, " << seam_report_.band_bonds << " bonds of "
            << seam_report_.band_particles << " particles within " << seam_balance_hops << " hops; out-of-balance force " << seam_report_.residual_before
            << " N -> " << seam_report_.residual_after << " N (" << seam_report_.iterations << " iterations)" << std::endl;
}

}  // namespace dfc::dem
