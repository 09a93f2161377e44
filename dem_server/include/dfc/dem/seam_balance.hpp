#pragma once
// Seam balance: bond loads that put the particles next to a seam back in
// equilibrium at the first step of a graded body (pcrm_zones.hpp).
//
// Why: each zone of a graded body is a replicated, loaded REV; where two
// zones meet, the finer one's spheres lost their neighbours (trimmed at the
// zone boundary, removed at the seam) and with them the loads those bonds
// carried. The seam bonds that join the zones form with zero load, so the
// spheres beside them start out of balance by the missing loads and the
// finer zone, the weaker of the two, relaxes laterally until the seam bonds
// take the load (the measured fine-zone σ_h fell to 0.78 K0 σ_v). The seam
// balance instead gives the bonds of a band around the seam the load changes
// that cancel the particles' out-of-balance forces, changing the REV's bonds
// as little as it can:
//
//   minimise Σ_b |Δf_b|² / c_b  subject to  Σ_b A_ib Δf_b = -r_i  for every particle i of the band that no wall holds,
//
// with A_ib = +1 (-1) if i is bond b's first (second) body. The weights 1/c_b
// say whose load may change: a bond the REV formed holds a loaded state
// (c_b = 1), a seam bond has none yet (c_b = seam_bond_conductance, below).
// The particles a wall holds take the rest (their contacts answer by a change
// of overlap): without that, the band's deficit of support at the first step
// (the floor carries 62 % of the small graded variant's weight then) would be
// spread over every particle as a body force, and the equilibration let the
// body sag (measured σ_v -20 %). The Lagrange conditions give
// Δf_b = c_b (y_second - y_first) with the weighted graph Laplacian L_c y = r
// on the free particles and y = 0 on the held ones (our rule: a weighted
// least-norm solution of the particles' force balance, the bond graph's
// incidence matrix A as the constraint). L_c is solved per Cartesian component
// by conjugate gradients with its diagonal as preconditioner, in a fixed
// order (deterministic).
//
// Each Δf_b is taken onto its bond with the displacement its law's
// stiffness gives it (ContactLawSetting::add_bond_load), so the state is
// one the bond could have reached elastically.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

/// Bond hops around the seam bonds' particles whose bonds the balance may
/// change. Why 3: the out-of-balance spheres are those that lost neighbours,
/// within one coarse sphere of the seam (the seam removals reach one coarse
/// radius, about two fine spheres), i.e. one or two hops from a seam bond;
/// one hop more lets the correction spread rather than sit on the seam bonds.
inline constexpr int seam_balance_hops = 3;

/// c_b of a seam bond against 1 for a bond of the REV. Why 100: the
/// correction should go onto the seam bonds, whose load is unknown, and leave
/// the REV's bonds, whose load is the prepared state, alone where it can.
/// Measured on the small graded variant (fine core r < 3 mm, 8-24 mm deep,
/// at the first step): σ_h/K0 γz 0.78 with c = 1, 0.94 with 10, 0.96 with 100
/// and 1000; the conjugate-gradient iterations grow with c (190 at 1, 897
/// at 1000), so 100 is where the state stops changing.
inline constexpr double seam_bond_conductance = 100.0;

using BondEnds = std::array<std::uint32_t, 2>;

/// What one seam balance did (Simulation::seam_balance_report).
struct SeamBalanceReport {
  std::size_t seam_bonds = 0;    ///< bonds between particles of different materials
  std::size_t band_bonds = 0;    ///< bonds whose load the balance changed (the seam's and those within seam_balance_hops)
  std::size_t band_particles = 0;
  std::size_t iterations = 0;
  double residual_before = 0.0;  ///< N, Σ |out-of-balance force| over the band's particles
  double residual_after = 0.0;   ///< N, the same after the balance
};

/// Particles at most `hops` bonds away from a particle marked in `seeds`.
[[nodiscard]] std::vector<bool> within_bond_hops(std::size_t particle_count, std::span<const BondEnds> bonds, const std::vector<bool>& seeds, int hops);

struct BondNetworkBalance {
  std::vector<Vec3> correction;  ///< N, per bond: Δf_b on its first body (the second takes -Δf_b)
  std::size_t iterations = 0;    ///< conjugate-gradient iterations (largest of the three components)
  double residual_before = 0.0;  ///< N, Σ_i |r_i| over the bonds' particles that no wall supports
  double residual_after = 0.0;   ///< N, Σ_i |r_i + Σ_b A_ib Δf_b| over them (what is left: the totals of unsupported components)
};

/// The least-norm bond-force corrections that cancel the out-of-balance
/// forces `residual` (per particle) of the bonds' particles that are not
/// `supported` (conjugate gradients to a relative 1e-12). A supported
/// particle (one a wall holds) takes what is left: its wall contact answers
/// by a change of overlap. A component of the bonds' graph with no supported
/// particle keeps its mean residual on every particle (bond loads are
/// internal forces: they cannot change its total).
[[nodiscard]] BondNetworkBalance balance_bond_network(std::size_t particle_count, std::span<const BondEnds> bonds, std::span<const double> conductance,
                                                      std::span<const Vec3> residual, const std::vector<bool>& supported);

}  // namespace dfc::dem
