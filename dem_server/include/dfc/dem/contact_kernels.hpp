#pragma once
// The per-contact loops, templated on the contact law (ContactLawKernel).
//
// The law is resolved once per step (std::visit in contact_forces.cpp); inside
// the loop `law.evaluate` is an inlined call on a value type. Each loop writes
// only its own contact's slots (and the pair loop the particle sums its range
// owns, contact_lists.hpp Incidence), so it is parallel without atomics and
// its results do not depend on the thread count.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/parallel.hpp"
#include "dfc/dem/contact_model.hpp"
#include "dfc/dem/contact_plane_rotation.hpp"
#include "dfc/dem/particle_loads.hpp"
#include "dfc/dem/particle_store.hpp"
#include "dfc/dem/periodic_cell.hpp"
#include "dfc/dem/triangle_geometry.hpp"
#include "dfc/dem/wall.hpp"

namespace dfc::dem {

/// The two bodies of pair (i, j) as a law sees them: radii and effective mass.
inline void set_pair_bodies(const ParticleStore& p, std::uint32_t i, std::uint32_t j, ContactKinematics& kin) noexcept {
  kin.effective_mass = p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
  kin.radius_first = p.radius[i];
  kin.radius_second = p.radius[j];
}

/// The law of each pair contact: one law for every pair (a single particle
/// material), or a table of pair laws indexed per contact
/// (PairContacts::law_index, particle_materials.hpp). The index is read only
/// where there is a table, a branch that goes the same way for a whole list.
template <ContactLawKernel Law>
struct PairLaws {
  const Law* table = nullptr;                ///< the single law, or pair_index order
  const std::uint16_t* index = nullptr;      ///< per contact; nullptr: always table[0]
  [[nodiscard]] const Law& operator[](std::size_t k) const noexcept { return index == nullptr ? table[0] : table[index[k]]; }
};

/// PairLaws over `table` for `pairs` (a single law when the table has one).
template <ContactLawKernel Law>
[[nodiscard]] PairLaws<Law> pair_laws(const std::vector<Law>& table, const PairContacts& pairs) noexcept {
  return {table.data(), table.size() > 1 && !pairs.law_index.empty() ? pairs.law_index.data() : nullptr};
}

/// Sets pairs.constants for the current lists (laws without pair constants:
/// none), on `threads` threads (each row from its pair alone).
template <ContactLawKernel Law>
void compute_pair_constants(const PairLaws<Law>& laws, const ParticleStore& p, PairContacts& pairs, int threads = 1) {
  if constexpr (HasPairConstants<Law>) {
    pairs.constants_stride = Law::constants_size;
    pairs.constants.resize(pairs.size() * Law::constants_size);
    const auto n = std::int64_t(pairs.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items)
    for (std::int64_t i = 0; i < n; ++i) {
      const auto k = std::size_t(i);
      ContactKinematics kin;
      set_pair_bodies(p, pairs.first[k], pairs.second[k], kin);
      laws[k].pair_constants(kin, pairs.constants.data() + k * Law::constants_size);
    }
  } else {
    pairs.constants_stride = 0;
    pairs.constants.clear();
  }
}

/// The same with one law for every pair.
template <ContactLawKernel Law>
void compute_pair_constants(const Law& law, const ParticleStore& p, PairContacts& pairs) {
  compute_pair_constants(PairLaws<Law>{&law, nullptr}, p, pairs);
}

/// Candidates classified per block of a range before any is evaluated
/// (evaluate_pair_contacts): about 40 % of the peer benchmark's candidates are
/// apart, in no predictable order. The short classifying loop has many
/// independent position loads in flight, and the heavy loop then runs over
/// the acting pairs only (measured on the peer benchmark, interleaved runs:
/// -11 % time unbonded, about -9 % bonded; docs/dem_benchmarks.md).
inline constexpr std::size_t pair_block_size = 256;

/// How many pairs ahead the classifying loop prefetches history rows, and
/// the doubles of a 64-byte cache line.
inline constexpr std::size_t pair_prefetch_distance = 8;
inline constexpr std::size_t doubles_per_cache_line = 8;

struct PairBlock {
  std::uint32_t acting[pair_block_size];   ///< offsets in the block of the candidates to evaluate, increasing
  std::uint32_t apart[pair_block_size];    ///< offsets of those that carry nothing this step, increasing
  Vec3 branch[pair_block_size];            ///< x_j - x_i (minimum image), by offset
  double distance2[pair_block_size];       ///< |branch|^2, by offset
  double distance[pair_block_size];        ///< |branch|, by offset, for laws that skip idle gaps (the classification needs it)
  std::size_t acting_count = 0;
  std::size_t apart_count = 0;
};

/// The acting pairs of a block go through the law in stages of this many:
/// first all their kinematics, then (RotatesInPlaneHistory) all their stored
/// in-plane vectors into the current contact planes, then the law itself.
/// Each stage is a short loop of independent iterations, so the divisions and
/// square roots of successive contacts overlap instead of each one stalling
/// its own contact (measured on the peer benchmark: docs/dem_benchmarks.md).
inline constexpr std::size_t pair_stage_size = 64;

struct PairStage {
  ContactKinematics kinematics[pair_stage_size];
  Vec3 point[pair_stage_size];  ///< contact points
};

/// Evaluates every pair candidate into outputs[0, pairs.size()), and adds
/// each contact's force and moment to the bodies Incidence::direct marks (the
/// prefix of their sums, particle_loads.hpp; p.force/moment must have been
/// started). Runs Incidence's ranges in parallel, each in increasing order.
/// Returns true if some overlap exceeded max_overlap_fraction of the smaller
/// radius (SimulationSettings::max_overlap_fraction).
/// Space: OpenSpace, or PeriodicSpace (periodic_cell.hpp): then the branch
/// vector is the minimum image, the relative velocity includes the cell's
/// affine flow, and out.shift[k] = (x_i + d) - x_j receives the image offset
/// of the second particle (its lever arm starts at x_j + shift).
///
/// record (contact_lists.hpp ContactRecord): gathered_only writes force,
/// point, couple and shift only for the pairs the integrator gathers.
///
/// Each range goes in blocks of pair_block_size: the candidates that carry
/// nothing (apart, or across a gap with no intact bond) are written as
/// separated first, then the acting ones are evaluated in increasing order.
/// The order of the additions into a particle is therefore that of the
/// acting contacts, as before; a separated pair adds only a +0 (step 2 in
/// the body), and where a +0 enters a sum does not change its bits.
template <ContactLawKernel Law, class Space = OpenSpace>
bool evaluate_pair_contacts(const PairLaws<Law>& laws, ParticleStore& p, PairContacts& pairs, const Incidence& incidence, ContactOutputs& out, double dt,
                            ContactRecord record, double max_overlap_fraction, int threads, const Space& space = {}) {
  const auto chunks = static_cast<std::int64_t>(incidence.pair_chunks());
  constexpr std::uint8_t both_direct = Incidence::direct_first | Incidence::direct_second;
  const bool record_all = record == ContactRecord::complete;
  // Whether pair k's outputs are written this step.
  const auto recorded = [&](std::size_t k) { return record_all || incidence.direct[k] != both_direct; };
  bool excessive = false;
#pragma omp parallel for schedule(static, 1) num_threads(threads) if(chunks > 1) reduction(|| : excessive)
  for (std::int64_t c = 0; c < chunks; ++c) {
    const std::size_t range_end = incidence.chunk_start[std::size_t(c) + 1];
    PairBlock block;
    PairStage stage;
    for (std::size_t first = incidence.chunk_start[std::size_t(c)]; first < range_end; first += pair_block_size) {
      const std::size_t count = std::min(pair_block_size, range_end - first);
      // 1. Classify (no branch on the outcome: both lists get a slot, one count moves).
      block.acting_count = block.apart_count = 0;
      for (std::size_t o = 0; o < count; ++o) {
        const std::size_t k = first + o;
        // The history row of a pair a few ahead, every cache line of it: this
        // loop reads each row's first line (a bond's state) and the stages
        // below the rest (not the cold row of a SplitsHistory law, read only by
        // the bonds that have yielded), and in a model larger than the caches those lines
        // come from memory (prefetch only: the same results). Bonded laws
        // only: an unbonded row is 3 doubles, and there the prefetches cost
        // more than they save (-4 to -5 % on the peer benchmark, docs/dem_benchmarks.md).
        if (Law::bonded && k + pair_prefetch_distance < range_end) {
          const double* ahead = pairs.row(k + pair_prefetch_distance);
          for (std::size_t line = 0; line < pairs.stride; line += doubles_per_cache_line) __builtin_prefetch(ahead + line, 1);
          __builtin_prefetch(ahead + pairs.stride - 1, 1);
          // and the second body's state, read here and in the kinematics (the
          // first bodies come in order, the second ones from around the model).
          const std::uint32_t j_ahead = pairs.second[k + pair_prefetch_distance];
          __builtin_prefetch(&p.position[j_ahead]);
          __builtin_prefetch(&p.velocity[j_ahead]);
          __builtin_prefetch(&p.angular_velocity[j_ahead]);
        }
        const std::uint32_t i = pairs.first[k];
        const std::uint32_t j = pairs.second[k];
        const Vec3 xi = p.position[i];
        const Vec3 d = space.branch(xi, p.position[j]);
        if constexpr (Space::periodic) {
          if (recorded(k)) out.shift[k] = (xi + d) - p.position[j];
        }
        const double reach = p.radius[i] + p.radius[j];
        const double dist2 = norm2(d);
        // 1 if the pair is evaluated, 0 if it carries nothing: an integer, so
        // that the counts move by arithmetic (with a bool GCC made a branch of it).
        std::size_t acting = 1;
        if constexpr (!Law::acts_across_gap) {
          acting = std::size_t(!(dist2 >= reach * reach));
        } else if constexpr (SkipsIdleGaps<Law>) {
          // The same test as the law's own (overlap <= 0), so the result is the law's.
          block.distance[o] = std::sqrt(dist2);
          acting = 1 - (std::size_t(reach - block.distance[o] <= 0.0) & std::size_t(Law::idle_across_gap(pairs.row(k))));
        }
        block.branch[o] = d;
        block.distance2[o] = dist2;
        block.acting[block.acting_count] = std::uint32_t(o);
        block.apart[block.apart_count] = std::uint32_t(o);
        block.acting_count += acting;
        block.apart_count += 1 - acting;
      }
      // 2. A pair that carries nothing this step: zero outputs, history reset.
      for (std::size_t a = 0; a < block.apart_count; ++a) {
        const std::size_t k = first + block.apart[a];
        const std::uint32_t i = pairs.first[k];
        if (recorded(k)) {
          out.force[k] = Vec3{};
          out.point[k] = p.position[i];
          if constexpr (Law::has_couple) out.couple[k] = Vec3{};
        }
        laws[k].separate(pairs.row(k));
        // The gather adds zeros here. Of those only the first body's +0 force
        // can change a bit (a -0 component of m g, from a -0 gravity component,
        // becomes +0); the second body's -0 leaves any value as it is, and so
        // do zero moments (a moment sum starts at +0, so it is never -0).
        if (incidence.direct[k] & Incidence::direct_first) p.force[i] += Vec3{};
      }
      // 3. The acting pairs, in increasing order, a stage at a time.
      for (std::size_t stage_first = 0; stage_first < block.acting_count; stage_first += pair_stage_size) {
        const std::size_t stage_count = std::min(pair_stage_size, block.acting_count - stage_first);
        // 3a. Kinematics.
        for (std::size_t a = 0; a < stage_count; ++a) {
          const std::size_t o = block.acting[stage_first + a];
          const std::size_t k = first + o;
          const std::uint32_t i = pairs.first[k];
          const std::uint32_t j = pairs.second[k];
          const Vec3 xi = p.position[i];
          const Vec3 d = block.branch[o];
          const double ri = p.radius[i];
          const double rj = p.radius[j];
          double dist = 0.0;
          if constexpr (SkipsIdleGaps<Law>) dist = block.distance[o];
          else dist = std::sqrt(block.distance2[o]);
          // Coincident centres have no direction; any fixed one keeps the run deterministic.
          const Vec3 normal = dist > 0.0 ? (1.0 / dist) * d : Vec3{0.0, 0.0, 1.0};
          ContactKinematics& kin = stage.kinematics[a];
          kin.normal = normal;
          kin.overlap = (ri + rj) - dist;
          excessive = excessive || kin.overlap > max_overlap_fraction * std::min(ri, rj);
          // Contact point in the middle of the overlap (PFC ball–ball convention).
          const Vec3 point = xi + (ri - 0.5 * kin.overlap) * normal;
          stage.point[a] = point;
          const Vec3 vi = p.velocity[i] + cross(p.angular_velocity[i], point - xi);
          // Centre of j's image next to i (j itself in open space, so those bits are unchanged).
          const Vec3 xj = Space::periodic ? xi + d : p.position[j];
          const Vec3 vj = p.velocity[j] + cross(p.angular_velocity[j], point - xj);
          kin.relative_velocity = vj - vi;
          if constexpr (Space::periodic) kin.relative_velocity += space.affine_velocity(d);
          kin.relative_angular_velocity = p.angular_velocity[j] - p.angular_velocity[i];
          kin.mean_spin_about_normal = mean_spin_about_normal(p.angular_velocity[i], p.angular_velocity[j], normal);
          set_pair_bodies(p, i, j, kin);
          kin.dt = dt;
        }
        // 3b. Stored in-plane vectors into the current contact planes.
        if constexpr (RotatesInPlaneHistory<Law>) {
          for (std::size_t a = 0; a < stage_count; ++a)
            rotate_in_plane_history<Law>(pairs.row(first + block.acting[stage_first + a]), stage.kinematics[a]);
        }
        // 3c. The law, the outputs and the loads.
        for (std::size_t a = 0; a < stage_count; ++a) {
          const std::size_t o = block.acting[stage_first + a];
          const std::size_t k = first + o;
          const std::uint32_t i = pairs.first[k];
          const std::uint32_t j = pairs.second[k];
          double* history = pairs.row(k);
          const ContactKinematics& kin = stage.kinematics[a];
          ContactForce f;
          const Law& law = laws[k];
          if constexpr (SplitsHistory<Law>) f = law.evaluate_in_plane(kin, pairs.constants_row(k), history, pairs.cold_row(k));
          else if constexpr (RotatesInPlaneHistory<Law>) f = law.evaluate_in_plane(kin, pairs.constants_row(k), history);
          else if constexpr (HasPairConstants<Law>) f = law.evaluate(kin, pairs.constants_row(k), history);
          else f = law.evaluate(kin, history);
          const Vec3 point = stage.point[a];
          if (recorded(k)) {
            out.force[k] = f.on_first;
            out.point[k] = point;
            if constexpr (Law::has_couple) out.couple[k] = f.couple_on_first;
          }
          // The same terms the gather would add.
          const std::uint8_t direct = incidence.direct[k];
          const Vec3 xi = p.position[i];
          if (direct & Incidence::direct_first) {
            add_contact_load(p.force[i], p.moment[i], f.on_first, point - xi);
            if constexpr (Law::has_couple) p.moment[i] += f.couple_on_first;
          }
          if (direct & Incidence::direct_second) {
            // Where j's lever arms start: its image next to i (j itself in open space).
            Vec3 xj_arm = p.position[j];
            if constexpr (Space::periodic) xj_arm = p.position[j] + ((xi + block.branch[o]) - p.position[j]);  // + shift, as above
            const Vec3 on_second = -1.0 * f.on_first;
            add_contact_load(p.force[j], p.moment[j], on_second, point - xj_arm);
            if constexpr (Law::has_couple) p.moment[j] += -1.0 * f.couple_on_first;
          }
        }
      }
    }
  }
  return excessive;
}

/// The same with one law for every pair.
template <ContactLawKernel Law, class Space = OpenSpace>
bool evaluate_pair_contacts(const Law& law, ParticleStore& p, PairContacts& pairs, const Incidence& incidence, ContactOutputs& out, double dt,
                            ContactRecord record, double max_overlap_fraction, int threads, const Space& space = {}) {
  return evaluate_pair_contacts(PairLaws<Law>{&law, nullptr}, p, pairs, incidence, out, dt, record, max_overlap_fraction, threads, space);
}

/// Evaluates the candidates of one wall into outputs[offset, offset + size).
/// select_wall_contacts must have run on this wall for the current positions
/// (it wrote the contact points into out.point). Returns true when an overlap
/// exceeded max_overlap_fraction of the particle's radius.
template <ContactLawKernel Law>
bool evaluate_wall_contacts(const Law& law, const ParticleStore& p, const Wall& wall, WallContacts& contacts, ContactOutputs& out,
                            std::size_t offset, double dt, double max_overlap_fraction, int threads) {
  const auto n = static_cast<std::int64_t>(contacts.size());
  bool excessive = false;
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items) reduction(|| : excessive)
  for (std::int64_t kk = 0; kk < n; ++kk) {
    const auto k = std::size_t(kk);
    const std::size_t o = offset + k;
    const std::uint32_t i = contacts.particle[k];
    double* history = contacts.row(k);
    const double ri = p.radius[i];
    const double overlap = ri - contacts.distance[k];
    if (contacts.selected[k] == 0 || (!Law::acts_across_gap && overlap <= 0.0)) {
      out.force[o] = Vec3{};
      if constexpr (Law::has_couple) out.couple[o] = Vec3{};
      law.separate(history);
      continue;
    }
    const Facet& f = wall.facets[contacts.facet[k]];
    const Vec3 xi = p.position[i];
    const Vec3 point = out.point[o];
    Vec3 normal;
    if (contacts.distance[k] > 0.0) {
      normal = (1.0 / contacts.distance[k]) * (point - xi);
    } else {  // centre on the facet: push along the facet normal (either side; fixed for determinism)
      normal = triangle_normal(wall.vertices[f[0]], wall.vertices[f[1]], wall.vertices[f[2]]);
    }
    const auto& w = contacts.weights[k];
    const Vec3 wall_velocity = w[0] * wall.vertex_velocity[f[0]] + w[1] * wall.vertex_velocity[f[1]] + w[2] * wall.vertex_velocity[f[2]];
    ContactKinematics kin;
    kin.normal = normal;
    kin.overlap = overlap;
    excessive = excessive || overlap > max_overlap_fraction * ri;
    kin.relative_velocity = wall_velocity - (p.velocity[i] + cross(p.angular_velocity[i], point - xi));
    kin.relative_angular_velocity = -p.angular_velocity[i];
    kin.mean_spin_about_normal = mean_spin_about_normal(p.angular_velocity[i], Vec3{}, normal);  // walls do not spin
    kin.effective_mass = p.mass[i];
    kin.radius_first = ri;
    kin.radius_second = 0.0;
    kin.dt = dt;
    const ContactForce result = law.evaluate(kin, history);
    out.force[o] = result.on_first;
    if constexpr (Law::has_couple) out.couple[o] = result.couple_on_first;
  }
  return excessive;
}

}  // namespace dfc::dem
