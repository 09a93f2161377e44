#pragma once
// Small builders shared by the DEM tests.
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "dfc/dem/contact_law_registry.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/model_builder.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem::test {

inline ContactLawSetting linear(double kn, double ks, double friction = 0.5, double damping_ratio = 0.0) {
  return make_contact_law({{"law", "linear"}, {"kn_n_m", kn}, {"ks_n_m", ks}, {"friction", friction}, {"damping_ratio_normal", damping_ratio}});
}

/// The damage-bond chalk of Ciantia et al. (2024) Table 1 (docs/references.md):
/// E*, kappa*, strengths, u_c and theta_c; u_c and the bond gap at S = 10.
inline ContactLawSetting chalk_at_s10() {
  return make_contact_law({{"law", "damage_bond"}, {"emod_pa", 1.7e9}, {"kratio", 5}, {"friction", 0.5}, {"bond_emod_pa", 1.7e9},
                           {"bond_kratio", 5}, {"ten_pa", 1e6}, {"com_pa", 5e7}, {"coh_pa", 2e6}, {"ucn_m", 2e-4}, {"ucs_m", 2e-4},
                           {"theta_c_rad", 0.006}, {"bond_gap_m", 2.62e-4}});
}

/// A simulation without gravity or local damping: the pure contact mechanics.
inline Simulation undamped(const ContactLawSetting& law, int threads = 1) {
  return Simulation(SimulationSettings{.particle_law = law, .gravity = {}, .local_damping = 0.0, .skin = 0.0, .threads = threads});
}

/// A lattice bed of spheres 3-4 mm in radius filling a cylinder 30 mm in
/// radius and 30 mm high, under 10 g, no walls: it falls freely (dem_backend
/// and foundation_loading tests add the walls they need).
inline nlohmann::json cylinder_bed_under_gravity() {
  return {
      {"particles",
       {{"generator", "lattice"},
        {"region", {{"type", "cylinder"}, {"radius_m", 0.03}, {"z_min_m", 0.0}, {"z_max_m", 0.03}}},
        {"radius_min_m", 0.003},
        {"radius_max_m", 0.004},
        {"density_kg_m3", 2650}}},
      {"contact", {{"kn_n_m", 1e5}, {"ks_n_m", 1e5}}},
      {"gravity_m_s2", {0, 0, -98.1}},
  };
}

/// 75 spheres (r 4.5-5 mm, 3 layers) in a 60 x 60 mm box on a frictional
/// floor with frictionless side walls: all the weight ends up on the floor.
/// A normal dashpot helps local damping settle it: the linear law has no
/// rolling or twisting resistance, so a sphere spinning about its contact
/// normals is stopped only by slow frictional sliding.
inline nlohmann::json box_bed_config() {
  const nlohmann::json smooth = {{"kn_n_m", 1e5}, {"ks_n_m", 2.5e4}, {"friction", 0.0}, {"damping_ratio_normal", 0.3}};
  return {
      {"particles",
       {{"generator", "lattice"},
        {"region", {{"type", "box"}, {"min_m", {0, 0, 0}}, {"max_m", {0.06, 0.06, 0.035}}}},
        {"radius_min_m", 0.0045},
        {"radius_max_m", 0.005},
        {"density_kg_m3", 2650},
        {"seed", 3}}},
      {"contact", {{"law", "linear"}, {"kn_n_m", 1e5}, {"ks_n_m", 2.5e4}, {"friction", 0.5}, {"damping_ratio_normal", 0.3}}},
      {"damping", {{"local", 0.7}}},
      {"timestep", {{"fraction_of_critical", 0.3}}},
      {"gravity_m_s2", {0, 0, -9.81}},
      {"walls",
       {{{"type", "plane"}, {"name", "floor"}, {"point_m", {0.03, 0.03, 0}}, {"normal", {0, 0, 1}}},
        {{"type", "plane"}, {"name", "x0"}, {"point_m", {0, 0.03, 0.06}}, {"normal", {1, 0, 0}}, {"contact", smooth}},
        {{"type", "plane"}, {"name", "x1"}, {"point_m", {0.06, 0.03, 0.06}}, {"normal", {-1, 0, 0}}, {"contact", smooth}},
        {{"type", "plane"}, {"name", "y0"}, {"point_m", {0.03, 0, 0.06}}, {"normal", {0, 1, 0}}, {"contact", smooth}},
        {{"type", "plane"}, {"name", "y1"}, {"point_m", {0.03, 0.06, 0.06}}, {"normal", {0, -1, 0}}, {"contact", smooth}}}},
  };
}

/// The box bed between two platens along z with a "ucs" section closing them
/// at a strain rate of 2 /s (the side walls removed).
inline nlohmann::json ucs_box_bed_config() {
  nlohmann::json c = box_bed_config();
  c["walls"] = nlohmann::json::array({
      {{"type", "plane"}, {"name", "bottom"}, {"point_m", {0, 0, -0.01}}, {"normal", {0, 0, 1}}},
      {{"type", "plane"}, {"name", "top"}, {"point_m", {0, 0, 0.5}}, {"normal", {0, 0, -1}}},
  });
  c["ucs"] = {{"top_wall", "top"}, {"bottom_wall", "bottom"}, {"strain_rate_per_s", 2.0}};
  return c;
}

struct SettledBed {
  Simulation simulation;
  double dt = 0.0;
  std::int64_t settle_steps = 0;
};

/// The box bed settled until the unbalanced-force ratio is below 1e-6 (built once per process).
inline const SettledBed& settled_box_bed() {
  static const SettledBed bed = [] {
    DemModel model = build_model(parse_dem_config(box_bed_config()));
    Simulation& sim = *model.simulation;
    std::int64_t steps = 0;
    while (steps < 400000) {
      sim.run(2000, model.dt);
      steps += 2000;
      if (measure(sim).unbalanced_force_ratio < 1e-6) break;
    }
    return SettledBed{sim, model.dt, steps};
  }();
  return bed;
}

/// A number as text with 4 significant digits, for RecordProperty.
inline std::string figure(double value) {
  std::ostringstream out;
  out.precision(4);
  out << value;
  return out.str();
}

}  // namespace dfc::dem::test
