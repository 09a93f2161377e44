// Triaxial compression in six rigid walls (triaxial_walls.hpp,
// docs/dem_triaxial_walls.md): the walls seated on the sample, the
// confinement stage (every wall at sigma_3, then bonds), and the shearing
// stage of the coupled advance (platens at the strain rate, lateral walls at
// sigma_3) with its stress, strain and porosity monitors.
#include <array>
#include <numbers>

#include "dfc/common/unit_names.hpp"
#include "dfc/dem/loading_protocol.hpp"
#include "dfc/dem/model_builder.hpp"
#include "dfc/dem/model_layout.hpp"

namespace dfc::dem {

namespace {

/// The servo of the confinement stage: every wall at sigma_3.
TriaxialControl triaxial_confinement(const TriaxialConfig& config, double max_strain_rate) {
  return {.confining_stress = config.confining_stress, .gain = config.servo_gain, .max_strain_rate = max_strain_rate, .platen_speed = std::nullopt};
}

/// ... and of the shearing stage: the platens close at rate H0/2 each (H0 the
/// platen separation at the end of the confinement), the lateral walls at sigma_3.
TriaxialControl triaxial_shearing(const TriaxialConfig& config, double max_strain_rate, double initial_height) {
  TriaxialControl control = triaxial_confinement(config, max_strain_rate);
  control.platen_speed = 0.5 * config.strain_rate * initial_height;  // dH/dt = -rate H0, the centre stays put
  return control;
}

class TriaxialLoading final : public LoadingProtocol {
 public:
  TriaxialLoading(const TriaxialConfig& config, const RadiusExpansionSpec& expansion) : config_(config), expansion_(expansion) {}

  [[nodiscard]] bool prepares_sample() const override { return true; }

  void arrange(ModelLayout& layout) override {
    if (!config_.seat_walls) return;
    const TriaxialWalls& w = config_.walls;
    const BoxAxes axes = box_axes(wall_box_vertices(layout.walls, w));
    seat_on_particles(layout.walls[w.top], layout.walls[w.bottom], layout.spheres, axes.axis);
    for (std::size_t p = 0; p < 2; ++p)
      seat_on_particles(layout.walls[w.lateral[2 * p + 1]], layout.walls[w.lateral[2 * p]], layout.spheres, axes.lateral[p]);
  }

  void prepare(DemModel& model, const PreparationInputs& inputs) override {
    Simulation& s = *model.simulation;
    model.preparation = confine_in_walls(s, config_.walls, triaxial_confinement(config_, model.max_strain_rate), config_.confinement,
                                         {inputs.final_radius, expansion_, inputs.fraction_of_critical}, model.dt);
    axes_ = box_axes(box_vertices(s.walls(), config_.walls));
    reference_ = box_size(s.walls(), config_.walls, axes_);
    control_ = triaxial_shearing(config_, model.max_strain_rate, reference_.height);
  }

  [[nodiscard]] bool drives_step() const override { return true; }
  void step(DemEngine& engine, double dt) override {
    const BoxStress box = triaxial_step(engine, config_.walls, axes_, control_, dt);
    axial_sum_ += box.axial();
    lateral_sum_ += box.lateral();
  }

  void averages(const DemEngine& /*engine*/, const AdvanceSums& sums, nlohmann::json& out) override {
    out["axial_stress_pa"] = sums.inv_steps * axial_sum_;
    out["lateral_stress_pa"] = sums.inv_steps * lateral_sum_;
    out["deviatoric_stress_pa"] = sums.inv_steps * (axial_sum_ - lateral_sum_);
    axial_sum_ = lateral_sum_ = 0.0;
  }

  void monitors(const DemEngine& engine, nlohmann::json& out) const override {
    const Simulation& s = engine.part();
    const BoxSize size = box_size(s.walls(), config_.walls, axes_);
    out["axial_strain"] = (reference_.height - size.height) / reference_.height;
    out["volumetric_strain"] = (reference_.volume() - size.volume()) / reference_.volume();
    // The spheres' volume summed exactly over the whole body (any process count gives its bits).
    const auto solid = body_accumulators<1>(engine, [&](std::size_t i) {
      const double r = s.particles().radius[i];
      return std::array<double, 1>{4.0 / 3.0 * std::numbers::pi * r * r * r};
    });
    out["porosity"] = box_porosity(solid[0].value(), size);
    if (out.contains("axial_stress_pa")) return;
    const BoxStress stress = box_stress(s.walls(), config_.walls, axes_, size);
    out["axial_stress_pa"] = stress.axial();
    out["lateral_stress_pa"] = stress.lateral();
    out["deviatoric_stress_pa"] = stress.deviator();
  }

  void progress_monitors(nlohmann::json& out) const override {
    out.push_back({{"monitor", "axial_strain"}, {"label", "axial strain"}, {"scale", 100.0}, {"unit", "%"}});
    out.push_back({{"monitor", "deviatoric_stress_pa"}, {"label", "q"}, {"scale", 1e-3}, {"unit", "kPa"}});
    out.push_back({{"monitor", "volumetric_strain"}, {"label", "volumetric strain"}, {"scale", 100.0}, {"unit", "%"}});
  }

 private:
  TriaxialConfig config_;
  RadiusExpansionSpec expansion_;  ///< a radius expansion inside the walls (the particles' spec)
  BoxAxes axes_;
  BoxSize reference_;        ///< at the end of the confinement: H0, W0, V0 of the strains
  TriaxialControl control_;  ///< shearing stage
  double axial_sum_ = 0.0, lateral_sum_ = 0.0;
};

}  // namespace

std::unique_ptr<LoadingProtocol> make_triaxial_loading(const DemConfig& config) {
  return config.triaxial ? std::make_unique<TriaxialLoading>(*config.triaxial, config.particles.expansion) : nullptr;
}

void declare_triaxial_monitors(nlohmann::json& units) {
  for (const char* stress : {"axial_stress_pa", "lateral_stress_pa", "deviatoric_stress_pa"}) units[stress] = unit::pascal;
  for (const char* ratio : {"axial_strain", "volumetric_strain", "porosity"}) units[ratio] = unit::dimensionless;
}

}  // namespace dfc::dem
