#pragma once
// Stress scaling of a replicated bonded body to the self-weight field at N g
// (docs/dem_generation.md §3).
//
// The REV carries sigma_ref = diag(K0, K0, 1) sigma_ref_v in its intact bonds
// (rev_preparation.hpp). For the laws whose intact bond force is a linear
// function of stored history alone (contact_law_registry.hpp
// ContactLawSetting::intact_force_from_history: soft_bond, damage_bond), the
// state with every stored force, moment, displacement and rotation of a bond
// multiplied by lambda is the state of the same bond under lambda times the
// load: force and the matching displacement change together, so it is a
// state of the law, not a force painted on. Each bond is scaled by
//   lambda = sigma_v(z_c) / sigma_ref_v,
// z_c its contact point, so the body's stress becomes sigma_v(z) on z and
// K0 sigma_v(z) on x and y (stress_profile.hpp). Because lambda varies
// linearly with depth, each sphere's scaled forces no longer cancel: to first
// order they leave lambda' sigma_ref_v V_sphere = gamma V_sphere upwards,
// which is the sphere's share of the body weight (Ciantia et al. 2018
// "scale the contact forces ... consistent with the gravitational field";
// the rule itself is ours: their paper does not give it). The short
// equilibration after generation removes the second-order remainder.
//
// Columns with unit "-" (bond state, damage) are never scaled; rows that are
// not intact bonds are left as they are (reported).
#include <cstddef>
#include <vector>

#include "dfc/dem/contact_model.hpp"
#include "dfc/dem/pcrm_replication.hpp"
#include "dfc/dem/stress_profile.hpp"

namespace dfc::dem {

struct StressScalingReport {
  std::size_t scaled_bonds = 0;
  std::size_t other_rows = 0;   ///< not intact: left unscaled
  double lambda_min = 0.0;
  double lambda_max = 0.0;
};

/// Scales `body`'s intact bond rows in place. `columns` is the particle law's
/// history layout; `reference_vertical` (Pa) the REV's sigma_v.
StressScalingReport scale_to_profile(ReplicatedBody& body, const std::vector<HistoryColumn>& columns, const StressProfile& profile,
                                     double reference_vertical);

}  // namespace dfc::dem
