#pragma once
// The representative element volume (REV) of the periodic cell replication
// method (PCRM; Ciantia, Arroyo, Zhang & Emam 2017, "Periodic cells for
// large-scale problem initialization", EPJ Web Conf. 140:15012,
// doi 10.1051/epjconf/201714015012; Ciantia et al. 2018, Proc. ICE Eng.
// Comput. Mech. 171(4):147-161, doi 10.1680/jencm.18.00025).
//
// Stages, each an existing preparation step (docs/dem_generation.md §1):
//   1. radius expansion to the target porosity in a periodic cell (unbonded);
//   2. isotropic servo consolidation to the installation stress sigma_0
//      (Potyondy & Cundall 2004, doi 10.1016/j.ijrmms.2004.09.011, §3.1
//      step 2: the packing is brought to a low isotropic stress, the same for
//      every test, before the bonds are installed). Unbonded, the packing
//      must compact from the expansion's loose state to a jammed one, and the
//      servo's compaction speed is proportional to the stress it aims at
//      (its strain step is the stress error over the stiffness): at the
//      mid-depth stress of a model at 10 g it never settled. At a fixed
//      sigma_0 the packing, its porosity and its steps are the same at every
//      g-level (docs/dem_generation.md, "Changing the g-level"). Isotropic:
//      a loose frictional packing held at a deviatoric K0 state creeps and
//      does not settle;
//   3. bonds within the bond gap, installed with zero load (the law's rule):
//      the packing's contact forces at sigma_0 leave with the installation
//      (an intact bond's force is its stored history alone), so nothing of
//      sigma_0 is locked in;
//   4. servo to the reference stress, now bonded: sigma_ref on z and
//      K0 sigma_ref on x and y (scaling it by a depth factor later gives
//      sigma_h = K0 sigma_v at every depth). The bonds take it up
//      elastically, so the bonded REV carries the reference stress in its
//      bonds' stored loads, in equilibrium (the elastic strain of this
//      stage changes the porosity by about sigma_ref / E).
// The result is the packing with every pair's history and the periodic image
// of each pair, which is what replication needs.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "dfc/dem/bed_generator.hpp"
#include "dfc/dem/periodic_config.hpp"
#include "dfc/dem/radius_expansion.hpp"
#include "dfc/dem/simulation.hpp"

namespace dfc::dem {

struct RevSpec {
  RadiusExpansionSpec particles;        ///< radii already upscaled
  PeriodicCell cell;                    ///< m, the cell before consolidation (periodic on x, y, z)
  double density = 0.0;                 ///< kg/m3, solid
  double servo_gain = sections::kDefaultServoGain;
  std::optional<double> max_strain_rate;  ///< 1/s; default 1e-4 / dt
  double installation_stress = sections::kDefaultRevInstallationStress;  ///< Pa, isotropic, of stage 2 (unbonded)
  ConsolidationSpec consolidation;      ///< stopping rule of both servo stages; loading: anisotropic sigma_ref
  double fraction_of_critical = sections::kDefaultFractionOfCritical;
};

/// A pair of the REV: local sphere indices (first has the smaller id) and the
/// cell image of the second sphere as seen from the first: the partner of
/// sphere `first` is sphere `second` shifted by image * L.
struct RevPair {
  std::uint32_t first = 0;
  std::uint32_t second = 0;
  std::array<int, 3> image{};
};

struct PreparedRev {
  PeriodicCell cell;                     ///< m, at the end (lo, hi; not deforming)
  std::vector<GeneratedSphere> spheres;  ///< wrapped into the cell; index = particle id in the REV
  std::size_t stride = 0;                ///< history doubles per pair (the particle law's)
  std::vector<RevPair> pairs;            ///< pairs with a non-zero history
  std::vector<double> rows;              ///< pairs.size() * stride
  Vec3 stress;                           ///< Pa, compression positive, cell stress diagonal at the end
  double porosity = 0.0;                 ///< 1 - sphere volume / cell volume
  std::int64_t bonds = 0;                ///< intact bonds
  std::int64_t damaged_bonds = 0;        ///< bonds that yielded (D > 0) under the deviatoric reference state
  std::int64_t steps = 0;                ///< all stages
  double dt = 0.0;                       ///< s, the step of the servo stages
};

/// Runs stages 1-4 with `settings` (its law; gravity is ignored inside the
/// cell). SolverError (naming `key`.consolidation) if a servo stage does not converge.
[[nodiscard]] PreparedRev prepare_rev(const RevSpec& spec, SimulationSettings settings, const std::string& key);

}  // namespace dfc::dem
