// The pile jacked into the particles (foundation_loading.hpp): its start rule
// and velocity ramp, the split of its force into tip and shaft (an open
// tube's annulus, inner and outer shaft) and the soil column in its bore.
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "dfc/common/unit_names.hpp"
#include "dfc/dem/foundation_loading.hpp"
#include "dfc/dem/inertial_number.hpp"
#include "dfc/dem/loading_protocol.hpp"
#include "dfc/dem/measurements.hpp"
#include "dfc/dem/model_builder.hpp"
#include "dfc/dem/pile_plug.hpp"

namespace dfc::dem {

namespace {

class PileLoading final : public LoadingProtocol {
 public:
  explicit PileLoading(const PileConfig& config) : config_(config) {}

  void prepare(DemModel& model, const PreparationInputs& /*inputs*/) override {
    wall_ = *model.pile_wall;
    const Wall& pile = model.simulation->walls()[wall_];
    reference_ = pile.vertices.front();
    tip_ = pile_tip_facets(pile, direction());
    if (config_.geometry.inner_radius > 0.0) {  // open tube: annulus, inner and outer shaft
      inner_ = pile_inner_facets(pile, config_.geometry.axis_x, config_.geometry.axis_y);
      outer_ = other_facets(pile, tip_, inner_);
    }
    waiting_ = config_.start_when.has_value();
    start_step_ = config_.start_step;
  }

  void before_advance(const DemEngine& engine, std::int64_t steps) override {
    const Simulation& s = engine.part();
    ramping_ = !waiting_ && s.step_count() + steps > start_step_ && s.step_count() < start_step_ + config_.ramp_steps;
  }

  void before_step(DemEngine& engine) override {
    Simulation& s = engine.part();
    // The loading stage's damping from the first moving step; set here each
    // step rather than once so that a run resumed from a checkpoint (which
    // restores waiting_ and start_step_, not the settings) has it too.
    if (config_.local_damping && !waiting_ && s.step_count() >= start_step_ && s.settings().local_damping != *config_.local_damping)
      s.set_local_damping(*config_.local_damping);
    if (ramping_ && s.step_count() >= start_step_)
      s.set_wall_velocity(wall_, ramped_velocity(config_.velocity, s.step_count() - start_step_, config_.ramp_steps));
  }

  void after_step(const DemEngine& engine) override {
    const Wall& pile = engine.part().walls()[wall_];
    tip_sum_ += facets_force(pile, tip_);
    inner_sum_ += facets_force(pile, inner_);
    outer_sum_ += facets_force(pile, outer_);
  }

  void end_advance(DemEngine& engine) override {
    Simulation& s = engine.part();
    if (!waiting_ || !pile_may_start(*config_.start_when, s.step_count(), config_.start_step, engine.measure().unbalanced_force_ratio)) return;
    start_step_ = s.step_count();
    s.set_wall_velocity(wall_, ramped_velocity(config_.velocity, 0, config_.ramp_steps));
    waiting_ = false;
    if (engine.rank() == 0) std::cerr << "dem_server: pile starts at step " << s.step_count() << " (pile.start_when met)" << std::endl;
  }

  void averages(const DemEngine& /*engine*/, const AdvanceSums& sums, nlohmann::json& out) override {
    const double inv_n = sums.inv_steps;
    const double total = -dot(inv_n * sums.wall_force[wall_], direction());
    const double tip = -dot(inv_n * tip_sum_, direction());
    out["pile_force_n"] = total;
    if (!(total <= peak_force_)) peak_force_ = total;  // NaN-safe: a first finite value replaces the initial NaN
    out["pile_tip_force_n"] = tip;
    out["pile_shaft_force_n"] = total - tip;
    if (!inner_.empty()) {  // an open tube: each shaft from its own facets (their sum is tested against the total)
      out["pile_inner_shaft_force_n"] = -dot(inv_n * inner_sum_, direction());
      out["pile_outer_shaft_force_n"] = -dot(inv_n * outer_sum_, direction());
    }
    tip_sum_ = inner_sum_ = outer_sum_ = Vec3{};
  }

  void monitors(const DemEngine& engine, nlohmann::json& out) const override {
    const Simulation& s = engine.part();
    const Vec3 moved = s.walls()[wall_].vertices.front() - reference_;
    out["pile_displacement_m"] = dot(moved, direction());
    out["pile_peak_force_n"] = std::isfinite(peak_force_) ? peak_force_ : 0.0;
    for (const char* force : {"pile_force_n", "pile_tip_force_n", "pile_shaft_force_n"})
      if (!out.contains(force)) out[force] = 0.0;
    out["pile_inertial_number"] = loading_inertial_number(engine, out["pile_tip_force_n"].get<double>());
    if (inner_.empty()) return;
    for (const char* force : {"pile_inner_shaft_force_n", "pile_outer_shaft_force_n"})
      if (!out.contains(force)) out[force] = 0.0;
    const PlugColumn plug = plug_column_of(engine, config_.geometry.tip_z + moved.z);
    out["pile_plug_length_m"] = plug.length;
    out["pile_plug_particles"] = plug.particles;
  }

  void progress_monitors(nlohmann::json& out) const override {
    out.push_back({{"monitor", "pile_displacement_m"}, {"label", "pile"}, {"scale", 1e3}, {"unit", "mm"}});
    out.push_back({{"monitor", "pile_force_n"}, {"label", "force"}, {"scale", 1.0}, {"unit", "N"}});
    out.push_back({{"monitor", "pile_peak_force_n"}, {"label", "peak"}, {"scale", 1.0}, {"unit", "N"}});
  }

  // Whether the pile still waits for pile.start_when, the step it started at, the peak force so far.
  void save_state(StateWriter& out) const override {
    out.value(waiting_);
    out.value(start_step_);
    out.value(peak_force_);
  }
  void load_state(StateReader& in) override {
    in.value(waiting_);
    in.value(start_step_);
    in.value(peak_force_);
  }

 private:
  /// The inertial number of the push (inertial_number.hpp): the shear rate v/D with
  /// v the pile's current speed (the ramp included) and D its outer diameter, the tip
  /// pressure over the flat end (an open tube's annulus). 0 while the pile rests. The
  /// grain scale is taken once the pile moves (the body is then complete; a resumed
  /// run takes it again from the same particles).
  [[nodiscard]] double loading_inertial_number(const DemEngine& engine, double tip_force) const {
    const Simulation& s = engine.part();
    const double speed = norm(s.walls()[wall_].prescribed_velocity);
    if (waiting_ || s.step_count() < start_step_ || !(speed > 0.0)) return 0.0;
    if (!grains_) grains_ = grain_scale_of(body_accumulators<4>(engine, [&](std::size_t i) { return grain_terms(s.particles(), i); }));
    const double r = config_.geometry.radius, ri = config_.geometry.inner_radius;
    const double tip_area = std::numbers::pi * (r * r - ri * ri);
    return inertial_number(speed / (2.0 * r), grains_->mean_diameter, tip_force / tip_area, grains_->density);
  }

  /// The soil column in the bore of the whole body, its tip at tip_z: every
  /// process's particles in the bore, gathered (the column's order is fixed by their tops).
  [[nodiscard]] PlugColumn plug_column_of(const DemEngine& engine, double tip_z) const {
    const std::vector<PlugTop> mine = plug_tops(engine.part().particles(), config_.geometry, tip_z, engine.owned());
    std::vector<double> flat;
    for (const PlugTop& top : mine) flat.insert(flat.end(), {top.z, top.volume, top.radius});
    const std::vector<double> all = engine.gather_over_processes(flat);
    std::vector<PlugTop> tops;
    for (std::size_t k = 0; k + 2 < all.size(); k += 3) tops.push_back({all[k], all[k + 1], all[k + 2]});
    return dfc::dem::plug_column_of(std::move(tops), config_.geometry, tip_z);
  }

  /// Unit vector of the pile's motion (its velocity direction; -z if it does not move).
  [[nodiscard]] Vec3 direction() const {
    const double speed = norm(config_.velocity);
    return speed > 0.0 ? (1.0 / speed) * config_.velocity : Vec3{0.0, 0.0, -1.0};
  }

  PileConfig config_;
  std::size_t wall_ = 0;            ///< the pile among the walls
  Vec3 reference_;                  ///< m, a pile vertex at the end of preparation
  std::vector<std::size_t> tip_;    ///< facets of the flat end (an open tube's annulus)
  std::vector<std::size_t> inner_;  ///< an open tube's inner-shaft facets (empty for a closed pile)
  std::vector<std::size_t> outer_;  ///< an open tube's outer-shaft facets
  bool waiting_ = false;            ///< pile.start_when given and not yet met
  std::int64_t start_step_ = 0;     ///< first moving step (start_step, or when start_when was met)
  bool ramping_ = false;            ///< this advance sets the ramped velocity
  double peak_force_ = std::numeric_limits<double>::quiet_NaN();  ///< N, largest advance-averaged pile force so far
  Vec3 tip_sum_, inner_sum_, outer_sum_;
  mutable std::optional<GrainScale> grains_;  ///< the body's grain scale, from the pile's first moving monitor
};

}  // namespace

std::unique_ptr<LoadingProtocol> make_pile_loading(const DemConfig& config) {
  return config.pile ? std::make_unique<PileLoading>(*config.pile) : nullptr;
}

void declare_pile_monitors(nlohmann::json& units) {
  for (const char* force : {"pile_force_n", "pile_tip_force_n", "pile_shaft_force_n", "pile_inner_shaft_force_n", "pile_outer_shaft_force_n"})
    units[force] = unit::newton;
  units["pile_plug_length_m"] = unit::metre;
  units["pile_plug_particles"] = unit::dimensionless;
  units["pile_displacement_m"] = unit::metre;
  units["pile_peak_force_n"] = unit::newton;
  units["pile_inertial_number"] = unit::dimensionless;
}

}  // namespace dfc::dem
