#include "dfc/dem/periodic_config.hpp"

#include <sstream>

#include "dfc/common/errors.hpp"

namespace dfc::dem {

namespace {

std::size_t read_axis(ConfigReader& cfg) {
  const std::string a = cfg.string("axis");
  return a == "x" ? 0 : a == "y" ? 1 : 2;
}

// The modes a section allows are its declaration's (dem.periodic.consolidation,
// dem.periodic.loading); each mode's keys are those of its variant.
CellLoading read_loading(ConfigReader& cfg) {
  CellLoading l;
  const std::string mode = cfg.string("mode");
  if (mode == "none") l.mode = CellLoading::Mode::none;
  if (mode == "isotropic") {
    l.mode = CellLoading::Mode::isotropic;
    l.stress = cfg.number("stress_pa");
  }
  if (mode == "k0") {
    l.mode = CellLoading::Mode::k0;
    l.stress = cfg.number("stress_pa");
    l.axis = read_axis(cfg);
  }
  if (mode == "anisotropic") {
    l.mode = CellLoading::Mode::anisotropic;
    l.stress = cfg.number("stress_pa");
    l.axis = read_axis(cfg);
    l.lateral_ratio = cfg.number("lateral_ratio");
  }
  if (mode == "triaxial") {
    l.mode = CellLoading::Mode::triaxial;
    l.stress = cfg.number("stress_pa");  // 0: unconfined (UCS of an REV)
    l.axial_rate = cfg.number("axial_strain_rate_per_s");
    if (l.axial_rate == 0.0)
      throw ConfigError(cfg.key_path("axial_strain_rate_per_s"),
                        "is 0: give a positive rate to compress the cell (triaxial compression, an unconfined REV's UCS) or a negative one to pull it (direct tension)");
    l.axis = read_axis(cfg);
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
  c.servo_gain = servo.number("gain");
  if (servo.has("max_strain_rate_per_s")) c.max_strain_rate = servo.number("max_strain_rate_per_s");
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
  const std::string axes = cfg.string("axes");
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
    s.loading = read_loading(r);
    static_cast<EquilibriumTarget&>(s) = read_equilibrium_target(r);
    r.finish();
    c.consolidation = s;
  }
  if (auto loading = cfg.optional_child("loading")) {
    c.loading = read_loading(*loading);
    loading->finish();
  }
  cfg.finish();
  return c;
}

RadiusExpansionSpec read_radius_expansion(ConfigReader& cfg) {
  RadiusExpansionSpec s;
  s.radius_min = cfg.number("radius_min_m");
  s.radius_max = cfg.number("radius_max_m");
  if (s.radius_max < s.radius_min) cfg.fail("radius_max_m", "must be at least radius_min_m");
  s.porosity = cfg.number("porosity");
  if (!(s.porosity < 1.0)) cfg.fail("porosity", "must be in (0, 1): a porosity of 1 leaves no solid");
  s.multiplier = cfg.number("multiplier");
  s.stages = int(cfg.integer("stages"));
  s.relax_steps = cfg.integer("relax_steps");
  s.seed = std::uint64_t(cfg.integer("seed"));
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

}  // namespace dfc::dem
