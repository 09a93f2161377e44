#include "dfc/dem/periodic_config.hpp"

#include <sstream>

#include "dfc/common/errors.hpp"

namespace dfc::dem {

namespace {

std::size_t read_axis(ConfigReader& cfg, std::string_view key) {
  const std::string a = cfg.choice(key, {"x", "y", "z"}, "z");
  return a == "x" ? 0 : a == "y" ? 1 : 2;
}

CellLoading read_loading(ConfigReader& cfg, const std::vector<std::string>& modes) {
  CellLoading l;
  const std::string mode = cfg.choice("mode", modes);
  if (mode == "none") l.mode = CellLoading::Mode::none;
  if (mode == "isotropic") {
    l.mode = CellLoading::Mode::isotropic;
    l.stress = cfg.positive("stress_pa");
  }
  if (mode == "k0") {
    l.mode = CellLoading::Mode::k0;
    l.stress = cfg.positive("stress_pa");
    l.axis = read_axis(cfg, "axis");
  }
  if (mode == "anisotropic") {
    l.mode = CellLoading::Mode::anisotropic;
    l.stress = cfg.positive("stress_pa");
    l.axis = read_axis(cfg, "axis");
    l.lateral_ratio = cfg.positive("lateral_ratio");
  }
  if (mode == "triaxial") {
    l.mode = CellLoading::Mode::triaxial;
    l.stress = cfg.number("stress_pa", Bounds{0.0});  // 0: unconfined (UCS of an REV)
    l.axial_rate = cfg.positive("axial_strain_rate_per_s");
    l.axis = read_axis(cfg, "axis");
  }
  if (mode == "strain_rate") {
    l.mode = CellLoading::Mode::strain_rate;
    const auto r = cfg.vec3("strain_rate_per_s");
    l.strain_rate = {r[0], r[1], r[2]};
  }
  return l;  // the caller reads its own keys and finishes
}

}  // namespace

void read_servo(ConfigReader servo, PeriodicConfig& c) {
  c.servo_gain = servo.number("gain", 0.5, Bounds{0.0, 1.0, true});
  if (servo.has("max_strain_rate_per_s")) c.max_strain_rate = servo.positive("max_strain_rate_per_s");
  else servo.accept("max_strain_rate_per_s");
  servo.finish();
}

PeriodicConfig read_periodic_config(ConfigReader cfg) {
  PeriodicConfig c;
  const auto lo = cfg.vec3("min_m");
  const auto hi = cfg.vec3("max_m");
  c.cell.lo = {lo[0], lo[1], lo[2]};
  c.cell.hi = {hi[0], hi[1], hi[2]};
  if (!(hi[0] > lo[0] && hi[1] > lo[1] && hi[2] > lo[2])) cfg.fail("max_m", "every component must exceed the one of min_m");
  const std::string axes = cfg.string("axes", "xyz");
  c.cell.periodic = {false, false, false};
  for (const char a : axes) {
    if (a != 'x' && a != 'y' && a != 'z') cfg.fail("axes", "use the letters x, y and z only, e.g. \"xyz\" or \"xy\" (a floor wall closes z)");
    c.cell.periodic[std::size_t(a - 'x')] = true;
  }
  if (!c.cell.any_periodic()) cfg.fail("axes", "name at least one periodic axis, e.g. \"xyz\"");
  if (auto servo = cfg.optional_child("servo")) read_servo(std::move(*servo), c);
  if (auto cons = cfg.optional_child("consolidation")) {
    ConfigReader& r = *cons;
    ConsolidationSpec s;
    s.loading = read_loading(r, {"isotropic", "k0", "anisotropic"});
    static_cast<EquilibriumTarget&>(s) = read_equilibrium_target(r);
    r.finish();
    c.consolidation = s;
  }
  if (auto loading = cfg.optional_child("loading")) {
    c.loading = read_loading(*loading, {"none", "isotropic", "k0", "anisotropic", "triaxial", "strain_rate"});
    loading->finish();
  }
  cfg.finish();
  return c;
}

RadiusExpansionSpec read_radius_expansion(ConfigReader& cfg) {
  RadiusExpansionSpec s;
  s.radius_min = cfg.positive("radius_min_m");
  s.radius_max = cfg.positive("radius_max_m");
  if (s.radius_max < s.radius_min) cfg.fail("radius_max_m", "must be at least radius_min_m");
  s.porosity = cfg.number("porosity", Bounds{0.0, 1.0, true});
  if (!(s.porosity > 0.0)) cfg.fail("porosity", "must be in (0, 1)");
  s.multiplier = cfg.number("multiplier", 1.6, Bounds{1.0, 10.0});
  s.stages = int(cfg.integer("stages", 10, 1));
  s.relax_steps = cfg.integer("relax_steps", 1000, 0);
  s.seed = std::uint64_t(cfg.integer("seed", 1, 0));
  return s;
}

void check_periodic_width(const PeriodicConfig& config, double r_max, double reach, const std::string& path) {
  const Vec3 l = config.cell.length();
  const double edge[3] = {l.x, l.y, l.z};
  const double need = 2.0 * (2.0 * r_max + reach);
  for (std::size_t a = 0; a < 3; ++a) {
    if (!config.cell.periodic[a] || edge[a] >= need) continue;
    std::ostringstream msg;
    msg << "the cell is " << edge[a] << " m long along the periodic axis " << "xyz"[a] << "; it must be at least 2 (2 r_max + skin) = " << need
        << " m (r_max " << r_max << " m, skin or bond gap " << reach << " m) so that every contact has one minimum image: widen the cell";
    throw ConfigError(path + "max_m", msg.str());
  }
}

CellServo make_servo(const CellLoading& l, double gain, double max_strain_rate) {
  switch (l.mode) {
    case CellLoading::Mode::isotropic: return CellServo::isotropic(l.stress, gain, max_strain_rate);
    case CellLoading::Mode::k0: return CellServo::k0(l.axis, l.stress, gain, max_strain_rate);
    case CellLoading::Mode::anisotropic: {
      CellServo s = CellServo::isotropic(l.lateral_ratio * l.stress, gain, max_strain_rate);
      s.axes.at(l.axis).value = l.stress;
      return s;
    }
    case CellLoading::Mode::triaxial: return CellServo::triaxial(l.axis, l.axial_rate, l.stress, gain, max_strain_rate);
    case CellLoading::Mode::strain_rate: {
      CellServo s{.gain = gain, .max_strain_rate = max_strain_rate};
      s.axes = {AxisControl{AxisMode::strain_rate, l.strain_rate.x}, AxisControl{AxisMode::strain_rate, l.strain_rate.y},
                AxisControl{AxisMode::strain_rate, l.strain_rate.z}};
      return s;
    }
    case CellLoading::Mode::none: break;
  }
  return CellServo{.gain = gain, .max_strain_rate = max_strain_rate};  // every edge at rate 0
}

std::string periodic_config_help() {
  return R"(  periodic        periodic (REV) cell, docs/dem_periodic.md:
                  {"min_m":[x,y,z], "max_m":[x,y,z] (required; each periodic edge >= 2 (2 r_max + skin)),
                   "axes":"xyz" (periodic axes; e.g. "xy" with a floor wall at z),
                   "servo":{"gain":0.5 (fraction of the stress error removed per step for an affine response, (0,1]),
                            "max_strain_rate_per_s" (cap of a stress-controlled edge; default 1e-4 / dt)},
                   "consolidation" (preparation, before the coupled run; bonds are installed after it):
                     {"mode":"isotropic"|"k0"|"anisotropic", "stress_pa" (p, or sigma_v on "axis":"z"),
                      "lateral_ratio" (anisotropic: the two other edges held at lateral_ratio x stress_pa), "tolerance":0.01 (relative
                      stress error), "unbalanced_force_ratio":0.01, "max_steps":200000, "check_every":100},
                   "loading" (during advance): {"mode":"none"|"isotropic"|"k0"|"anisotropic"|"triaxial"|"strain_rate",
                     "stress_pa" (p, sigma_v, or sigma_3 of triaxial: 0 = unconfined), "axis":"z" (k0, triaxial),
                     "axial_strain_rate_per_s" (triaxial: compression > 0), "strain_rate_per_s":[x,y,z] (strain_rate:
                     edge rates, extension positive)}}
                  adds the monitors cell_stress_xx/yy/zz_pa (Love-Weber over particle contacts, compression
                  positive, averaged over the advance), cell_strain_xx/yy/zz (engineering, (L0 - L)/L0 from the
                  end of preparation, compression positive), porosity (1 - sphere volume / cell volume)
)";
}

}  // namespace dfc::dem
