#pragma once
// The fdm_server scenario section: schema, parsing and --help text.
//
// {
//   "mesh": {"type": "box", "origin_m": [x,y,z] (default [0,0,0]), "size_m": [Lx,Ly,Lz] (> 0),
//            "zones": [nx,ny,nz] (integers >= 1), "grading": [gx,gy,gz] (default [1,1,1])}
//        or {"type": "cylinder_cavity", "inner_radius_m": Ri, "outer_radius_m": Ro (> Ri),
//            "z_bottom_m": 0, "height_m": H, "zones_radial": nr, "zones_around": nθ (>= 3 for 360°),
//            "zones_vertical": nz, "grading_ratio": 1 (Δr_{k+1}/Δr_k outwards; > 1 = finer at the cavity),
//            "angle_deg": 360 (a sector adds groups theta_min/theta_max), "max_aspect_ratio": 10,
//            "cavity_floor_z_m": z_bottom_m (above it: the cavity ends there, on a solid O-grid base)}
//        or {"type": "sphere_cavity_octant", "inner_radius_m", "outer_radius_m", "zones_radial",
//            "zones_around", "grading_ratio", "max_aspect_ratio"},
//   "material": {"model": "elastic" | "mohr_coulomb" | "structured_cam_clay", "density_kg_m3": ρ,
//                <the model's parameters>}  or  {"preset": "chalk_snw", <overrides>},
//   "gravity_m_s2": [0,0,0]          total acceleration vector (the coupler injects N·g here),
//   "damping": {"local": 0.8}         local damping α in [0,1) (§1.9),
//   "mass_scaling": true              scale inertial masses so any Δt is stable (§1.10),
//   "threads": 0                      OpenMP threads, 0 = OpenMP default,
//   "boundaries": [{"group": "zmin", "condition": "fixed" | "roller" | "pressure" | "traction",
//                   "pressure_pa": p (pressure only, > 0 pushes into the body),
//                   "traction_pa": [tx,ty,tz] (traction only)}, ...]   (default none),
//   "initial_stress": {"type": "geostatic", "k0": K0 (>= 0), "z_top_m": (default: top of the mesh)},
//   "coupling": {"role": "provider" | "driven", "group": "<face group>"}   (absent: standalone)
// }
// Every object is checked for unknown keys; errors are dfc::ConfigError with
// the key path relative to the section ("boundaries[1].group").
#include <string>

#include <nlohmann/json.hpp>

#include "dfc/fdm/solver.hpp"

namespace dfc {
class ConfigReader;
}

namespace dfc::fdm {

enum class CouplingRole {
  none,      ///< standalone: advance takes no inputs
  provider,  ///< provides the interface mesh; advance: force (+mass) in, velocity/displacement out
  driven,    ///< accepts the partner's interface; advance: velocity in, force/mass out
};

struct CouplingSettings {
  CouplingRole role = CouplingRole::none;
  std::string group;  ///< the coupling face group
};

struct FdmModel {
  Solver solver;
  CouplingSettings coupling;
};

/// Parses and validates the section and builds the solver with its boundary
/// conditions and initial stress. Throws dfc::ConfigError naming the key path.
[[nodiscard]] FdmModel load_fdm_model(const nlohmann::json& section);

/// Parses the "material" object of the section alone (a model and its
/// parameters, or a preset with overrides), e.g. for element tests. Throws
/// dfc::ConfigError with key paths under "material".
[[nodiscard]] Material load_fdm_material(const nlohmann::json& material);

/// The optional "damping" object of a section (sections::fdm_damping(), also
/// continuum_server's): the local damping coefficient α in [0, 1).
[[nodiscard]] double read_local_damping(ConfigReader& root);

/// The --help description of the section, including the constitutive models
/// of the registry with their parameters and units.
[[nodiscard]] std::string fdm_config_help();

}  // namespace dfc::fdm
