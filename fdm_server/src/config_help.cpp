// The --help text of the fdm_server section; the model list comes from the registry.
#include "dfc/fdm/fdm_config.hpp"
#include "dfc/fdm/model_registry.hpp"
#include "dfc/fdm/named_materials.hpp"

namespace dfc::fdm {

std::string fdm_config_help() {
  return R"(  (a JSON object; unknown keys are errors, key paths are named in the error)
  mesh            object, required. One of
                    {"type": "box", "origin_m": [x,y,z] (m, default [0,0,0]),
                     "size_m": [Lx,Ly,Lz] (m, > 0), "zones": [nx,ny,nz] (integers >= 1),
                     "grading": [gx,gy,gz] (spacing growth per zone along +x,+y,+z, default [1,1,1])}
                      face groups: xmin xmax ymin ymax zmin zmax
                    {"type": "cylinder_cavity", "inner_radius_m": Ri (m), "outer_radius_m": Ro (m, > Ri),
                     "z_bottom_m": (m, default 0), "height_m": H (m), "zones_radial": (>= 1),
                     "zones_around": (>= 3 for 360 deg, >= 1 for a sector), "zones_vertical": (>= 1),
                     "grading_ratio": (dr[k+1]/dr[k] counted outwards, > 1 = finer at the cavity, default 1),
                     "angle_deg": (the sector 0..angle_deg, in (0, 360], default 360),
                     "max_aspect_ratio": (largest longest/shortest zone edge allowed, >= 1, default 10),
                     "cavity_floor_z_m": (m, default z_bottom_m = the cavity through the whole height;
                                          above it: the cavity ends there, a solid base below it;
                                          below z_bottom + H, on a zone level z_bottom + k H/zones_vertical;
                                          needs angle_deg 360 and zones_around a multiple of 4)}
                      face groups: inner outer bottom top, and theta_min theta_max for a sector;
                      with a cavity floor "inner" is the cavity's side and floor, also apart as
                      cavity_side cavity_floor
                    {"type": "sphere_cavity_octant", "inner_radius_m": Ri (m), "outer_radius_m": Ro (m, > Ri),
                     "zones_radial": (>= 1), "zones_around": (zones per patch edge, 3 patches, >= 1),
                     "grading_ratio": (default 1), "max_aspect_ratio": (default 10)}
                      the octant x, y, z >= 0 of a spherical shell; face groups: inner outer xmin ymin zmin
  material        object, required: {"model": <keyword>, "density_kg_m3": rho (kg/m3, > 0), <model parameters>}
                  or {"preset": <named material>, <keys overriding the preset's values>}
  gravity_m_s2    [gx,gy,gz] total acceleration, m/s2 (default [0,0,0]; the coupler passes N*g here)
  damping         {"local": alpha} local non-viscous damping in [0,1) (default 0.8)
  mass_scaling    true|false (default true): scale inertial masses so any dt is stable (quasi-static);
                  false: real masses, dt must not exceed dt_max
  threads         OpenMP threads, 0..1024, 0 = OpenMP default (default 0)
  boundaries      array (default none) of {"group": <face group>, "condition": c, ...} with c one of
                    "fixed"     all velocity components zero
                    "roller"    zero normal velocity (axis-aligned plane) or zero radial velocity
                                (cylindrical group about z, e.g. "outer")
                    "pressure"  "pressure_pa": p (Pa, > 0 pushes into the body)
                    "traction"  "traction_pa": [tx,ty,tz] (Pa, force per area on the face)
  initial_stress  {"type": "geostatic", "k0": K0 (>= 0), "z_top_m": (m, default top of the mesh)}:
                  sigma_v = rho |g| (z_top - z), sigma_h = K0 sigma_v (compression); needs gravity along -z
  coupling        {"role": "provider"|"driven", "group": <face group>} (absent: standalone)
                    provider: advance takes force [n,3] N (+ optional mass [n] kg), returns velocity, displacement
                    driven:   advance takes velocity [n,3] m/s, returns force [n,3] N and mass [n] kg
Stresses are tension positive (Pa). Constitutive models ("material.model"):
)" + describe_constitutive_models() + "Named materials (\"material.preset\"):\n" + describe_named_materials();
}

}  // namespace dfc::fdm
