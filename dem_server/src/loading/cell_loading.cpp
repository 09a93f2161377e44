// A periodic cell (docs/dem_periodic.md): its preparation (radius expansion,
// servo consolidation, bonds), its loading during the coupled advance by the
// cell servo (cell_servo.hpp), and the cell's stress, strain and porosity
// monitors.
#include "dfc/common/unit_names.hpp"
#include "dfc/dem/cell_stress.hpp"
#include "dfc/dem/loading_protocol.hpp"
#include "dfc/dem/model_builder.hpp"

namespace dfc::dem {

namespace {

class PeriodicCellLoading final : public LoadingProtocol {
 public:
  PeriodicCellLoading(const PeriodicConfig& config, const RadiusExpansionSpec& expansion, bool expands, bool axial_monitors)
      : config_(config), expansion_(expansion), expands_(expands), axial_monitors_(axial_monitors) {}

  [[nodiscard]] bool prepares_sample() const override { return expands_ || config_.consolidation.has_value(); }

  void prepare(DemModel& model, const PreparationInputs& inputs) override {
    Simulation& s = *model.simulation;
    if (prepares_sample())
      model.preparation = prepare_sample(s, config_, inputs.final_radius, expansion_, inputs.fraction_of_critical, model.dt, model.max_strain_rate);
    servo_ = make_servo(config_.loading, config_.servo_gain, model.max_strain_rate);
    reference_length_ = s.periodic_cell()->length();
  }

  [[nodiscard]] bool drives_step() const override { return true; }
  // A periodic cell runs on one process (DistributedSimulation refuses it): its part is the whole body.
  void step(DemEngine& engine, double dt) override { stress_sum_ += servo_step(engine.part(), servo_, dt).diagonal(); }

  void averages(const DemEngine& /*engine*/, const AdvanceSums& sums, nlohmann::json& out) override {
    out["cell_stress_xx_pa"] = sums.inv_steps * stress_sum_.x;
    out["cell_stress_yy_pa"] = sums.inv_steps * stress_sum_.y;
    out["cell_stress_zz_pa"] = sums.inv_steps * stress_sum_.z;
    stress_sum_ = Vec3{};
  }

  void monitors(const DemEngine& engine, nlohmann::json& out) const override {
    const Simulation& s = engine.part();
    const PeriodicCell& cell = *s.periodic_cell();
    const Vec3 l = cell.length();
    const Vec3& l0 = reference_length_;
    out["cell_strain_xx"] = (l0.x - l.x) / l0.x;
    out["cell_strain_yy"] = (l0.y - l.y) / l0.y;
    out["cell_strain_zz"] = (l0.z - l.z) / l0.z;
    out["porosity"] = cell_porosity(s.particles(), cell);
    if (!out.contains("cell_stress_xx_pa")) {
      const Vec3 stress = measure_cell_stress(s).diagonal();
      out["cell_stress_xx_pa"] = stress.x;
      out["cell_stress_yy_pa"] = stress.y;
      out["cell_stress_zz_pa"] = stress.z;
    }
    // Triaxial (or unconfined, sigma_3 = 0) loading of the REV: the same
    // axial monitors as a platen test (ucs_platens.hpp), so one plot and one
    // calibration procedure serve both, plus the deviator q = sigma_a - sigma_3
    // (sigma_3 the mean of the two lateral stresses).
    if (!axial_monitors_ || config_.loading.mode != CellLoading::Mode::triaxial) return;
    static constexpr const char* stress_keys[3] = {"cell_stress_xx_pa", "cell_stress_yy_pa", "cell_stress_zz_pa"};
    static constexpr const char* strain_keys[3] = {"cell_strain_xx", "cell_strain_yy", "cell_strain_zz"};
    const std::size_t a = config_.loading.axis;
    const double axial = out[stress_keys[a]].get<double>();
    const double lateral = 0.5 * (out[stress_keys[(a + 1) % 3]].get<double>() + out[stress_keys[(a + 2) % 3]].get<double>());
    out["axial_stress_pa"] = axial;
    out["axial_strain"] = out[strain_keys[a]];
    out["deviatoric_stress_pa"] = axial - lateral;
  }

 private:
  PeriodicConfig config_;
  RadiusExpansionSpec expansion_;
  bool expands_;          ///< generator "radius_expansion": the preparation grows the spheres first
  bool axial_monitors_;   ///< no "ucs" section sends axial_stress_pa and axial_strain
  CellServo servo_;
  Vec3 reference_length_;  ///< m, cell edges at the end of preparation
  Vec3 stress_sum_;
};

}  // namespace

std::unique_ptr<LoadingProtocol> make_cell_loading(const DemConfig& config) {
  if (!config.periodic) return nullptr;
  return std::make_unique<PeriodicCellLoading>(*config.periodic, config.particles.expansion, config.particles.generator == "radius_expansion",
                                       !config.ucs.has_value());
}

void declare_cell_monitors(nlohmann::json& units) {
  for (const char* stress : {"cell_stress_xx_pa", "cell_stress_yy_pa", "cell_stress_zz_pa", "axial_stress_pa", "deviatoric_stress_pa"})
    units[stress] = unit::pascal;
  for (const char* ratio : {"cell_strain_xx", "cell_strain_yy", "cell_strain_zz", "porosity", "axial_strain"}) units[ratio] = unit::dimensionless;
}

}  // namespace dfc::dem
