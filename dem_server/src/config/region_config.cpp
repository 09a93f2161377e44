#include "dfc/dem/region_config.hpp"

namespace dfc::dem {

namespace {
Vec3 to_vec3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
}  // namespace

std::array<double, 2> read_xy(ConfigReader& cfg, std::string_view key) {
  const auto v = cfg.numbers(key);  // declared with its default [0, 0]
  if (v.size() != 2) cfg.fail(key, "expected an array of 2 numbers [x, y]");
  return {v[0], v[1]};
}

BedRegion read_region(ConfigReader cfg) {
  BedRegion region;
  const std::string type = cfg.string("type");
  if (type == "box") {
    region.shape = BedRegion::Shape::box;
    region.min = to_vec3(cfg.vec3("min_m"));
    region.max = to_vec3(cfg.vec3("max_m"));
    if (!(region.max.x > region.min.x && region.max.y > region.min.y && region.max.z > region.min.z))
      cfg.fail("max_m", "every component must exceed the one of min_m");
  } else {
    region.shape = BedRegion::Shape::cylinder;
    const auto axis = read_xy(cfg, "axis_xy_m");
    region.axis_x = axis[0];
    region.axis_y = axis[1];
    region.radius = cfg.number("radius_m");
    region.z_min = cfg.number("z_min_m");
    region.z_max = cfg.number("z_max_m");
    if (!(region.z_max > region.z_min)) cfg.fail("z_max_m", "must exceed z_min_m");
  }
  cfg.finish();
  return region;
}

std::pair<Vec3, Vec3> region_bounds(const BedRegion& r) {
  if (r.shape == BedRegion::Shape::box) return {r.min, r.max};
  return {{r.axis_x - r.radius, r.axis_y - r.radius, r.z_min}, {r.axis_x + r.radius, r.axis_y + r.radius, r.z_max}};
}

}  // namespace dfc::dem
