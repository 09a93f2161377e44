// Uniaxial compression between two platens (ucs_platens.hpp, docs/dem_ucs.md):
// the platens seated on the sample and set closing at the strain rate, the
// sample's cross-section, and the axial stress and strain monitors.
#include <cmath>
#include <numbers>

#include "dfc/common/unit_names.hpp"
#include "dfc/dem/loading_protocol.hpp"
#include "dfc/dem/model_builder.hpp"
#include "dfc/dem/model_layout.hpp"
#include "dfc/dem/ucs_platens.hpp"

namespace dfc::dem {

namespace {

/// Cross-section of the sample normal to z (ucs_area_derivable: a lattice bed,
/// platens normal to z): a disc through the outermost particle of a
/// cylindrical bed, the particles' x–y bounding box of a box bed.
double derived_area(std::span<const GeneratedSphere> spheres, const BedRegion& region) {
  if (region.shape == BedRegion::Shape::cylinder) {
    double radius = 0.0;
    for (const auto& s : spheres) radius = std::max(radius, std::hypot(s.centre.x - region.axis_x, s.centre.y - region.axis_y) + s.radius);
    return std::numbers::pi * radius * radius;
  }
  double lo_x = INFINITY, lo_y = INFINITY, hi_x = -INFINITY, hi_y = -INFINITY;
  for (const auto& s : spheres) {
    lo_x = std::min(lo_x, s.centre.x - s.radius);
    lo_y = std::min(lo_y, s.centre.y - s.radius);
    hi_x = std::max(hi_x, s.centre.x + s.radius);
    hi_y = std::max(hi_y, s.centre.y + s.radius);
  }
  return (hi_x - lo_x) * (hi_y - lo_y);
}

class UcsLoading final : public LoadingProtocol {
 public:
  UcsLoading(const UcsConfig& config, const BedRegion& region) : config_(config), region_(region), area_(config.area) {}

  void arrange(ModelLayout& layout) override {
    WallConfig& top = layout.walls[config_.top_wall];
    WallConfig& bottom = layout.walls[config_.bottom_wall];
    PlatenAxis axis = platen_axis(top.mesh.vertices, bottom.mesh.vertices);
    if (!(area_ > 0.0)) area_ = derived_area(layout.spheres, region_);
    if (config_.seat_platens) {
      seat_on_particles(top, bottom, layout.spheres, axis.axis);
      axis = platen_axis(top.mesh.vertices, bottom.mesh.vertices);
    }
    if (!config_.strain_rate) return;
    // Each platen moves half the closing speed dH/dt = -rate H0, so the sample
    // centre stays put and the platens load it symmetrically.
    const double speed = 0.5 * *config_.strain_rate * axis.initial_height;
    top.velocity = -speed * axis.axis;
    bottom.velocity = speed * axis.axis;
    top.start_step = bottom.start_step = config_.start_step;
  }

  void prepare(DemModel& model, const PreparationInputs& /*inputs*/) override {
    // build_model adds the configured walls first, in order: the same indices.
    const auto& walls = model.simulation->walls();
    axis_ = platen_axis(walls[config_.top_wall].vertices, walls[config_.bottom_wall].vertices);
  }

  void averages(const DemEngine& /*engine*/, const AdvanceSums& sums, nlohmann::json& out) override {
    out["axial_stress_pa"] = axial_stress(axis_, sums.inv_steps * sums.wall_force[config_.top_wall],
                                          sums.inv_steps * sums.wall_force[config_.bottom_wall], area_);
  }

  void monitors(const DemEngine& engine, nlohmann::json& out) const override {
    const Wall& top = engine.part().walls()[config_.top_wall];
    const Wall& bottom = engine.part().walls()[config_.bottom_wall];
    out["axial_strain"] = axial_strain(axis_, platen_separation(axis_, top.vertices, bottom.vertices));
    if (!out.contains("axial_stress_pa")) out["axial_stress_pa"] = axial_stress(axis_, top.force, bottom.force, area_);
  }

  void progress_monitors(nlohmann::json& out) const override {
    out.push_back({{"monitor", "axial_strain"}, {"label", "axial strain"}, {"scale", 100.0}, {"unit", "%"}});
    out.push_back({{"monitor", "axial_stress_pa"}, {"label", "stress"}, {"scale", 1e-3}, {"unit", "kPa"}});
  }

 private:
  UcsConfig config_;
  BedRegion region_;     ///< the lattice bed's region (derived area)
  double area_;          ///< m2, given, or derived when the layout is arranged
  PlatenAxis axis_;      ///< the platens at the end of preparation
};

}  // namespace

std::unique_ptr<LoadingProtocol> make_ucs_loading(const DemConfig& config) {
  return config.ucs ? std::make_unique<UcsLoading>(*config.ucs, config.particles.lattice.region) : nullptr;
}

void declare_ucs_monitors(nlohmann::json& units) {
  units["axial_stress_pa"] = unit::pascal;
  units["axial_strain"] = unit::dimensionless;
}

}  // namespace dfc::dem
