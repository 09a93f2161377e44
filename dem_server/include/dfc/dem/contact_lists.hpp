#pragma once
// Contact candidate lists, their per-contact history, the per-contact force
// storage and the particle -> contact incidence used for the gather.
//
// Why this shape: forces are computed per contact in parallel into
// ContactOutputs (no two threads write the same slot), and every particle
// sums its own contacts in the fixed order of Incidence (most of them inside
// the pair loop, the rest in a gather; see Incidence). No atomics, no
// thread-dependent summation order: results are bit-identical for any thread
// count (CONTRIBUTING.md §11).
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "dfc/dem/particle_store.hpp"
#include "dfc/dem/uninitialised_allocator.hpp"

namespace dfc::dem {

/// Particle–particle candidates. Oriented by id (id[first] < id[second]) so a
/// contact's history keeps its meaning when slots are re-sorted.
struct PairContacts {
  std::vector<std::uint32_t> first;
  std::vector<std::uint32_t> second;
  /// History doubles per contact in `history`: the law's history_size less
  /// its cold columns (contact_model.hpp SplitsHistory).
  std::size_t stride = 0;
  /// size() * stride, row per contact. Left uninitialised when resized: a
  /// rebuild writes every row in parallel (move_matched_rows, restore_history).
  UninitialisedDoubles history;
  /// The law's cold columns (contact_model.hpp SplitsHistory), size() *
  /// cold_stride, row per contact; empty for most laws. A contact's whole
  /// row is its `history` row followed by this one (whole_row).
  std::size_t cold_stride = 0;
  UninitialisedDoubles cold_history;
  /// The law's pair constants (contact_model.hpp HasPairConstants), row per
  /// contact of constants_stride doubles; every row set, in parallel, at
  /// every list rebuild (compute_pair_constants), so left uninitialised when resized.
  std::size_t constants_stride = 0;
  UninitialisedDoubles constants;
  /// Per contact, the index of its pair law (ParticleMaterials::pair_index of
  /// the two particles' materials); empty with a single material. Set at
  /// every list rebuild.
  std::vector<std::uint16_t> law_index;

  [[nodiscard]] std::size_t size() const noexcept { return first.size(); }
  [[nodiscard]] double* row(std::size_t k) noexcept { return history.data() + k * stride; }
  [[nodiscard]] const double* row(std::size_t k) const noexcept { return history.data() + k * stride; }
  [[nodiscard]] double* cold_row(std::size_t k) noexcept { return cold_history.data() + k * cold_stride; }
  [[nodiscard]] const double* constants_row(std::size_t k) const noexcept { return constants.data() + k * constants_stride; }
  /// Doubles of a whole row (the law's history_size).
  [[nodiscard]] std::size_t whole_stride() const noexcept { return stride + cold_stride; }
  /// Sets the row widths of `law_history_size` doubles, the last `cold_size` of them cold.
  void set_strides(std::size_t law_history_size, std::size_t cold_size) noexcept {
    stride = law_history_size - cold_size;
    cold_stride = cold_size;
  }
  /// Sizes both history arrays for size() contacts, uninitialised.
  void resize_history();
  /// Contact k's whole row into out (whole_stride() doubles).
  void copy_whole_row(std::size_t k, double* out) const noexcept {
    std::copy_n(history.data() + k * stride, stride, out);
    std::copy_n(cold_history.data() + k * cold_stride, cold_stride, out + stride);
  }
  /// Sets contact k's whole row from `whole` (whole_stride() doubles), or to zeros for nullptr.
  void set_whole_row(std::size_t k, const double* whole) noexcept {
    if (whole) {
      std::copy_n(whole, stride, row(k));
      std::copy_n(whole + stride, cold_stride, cold_row(k));
    } else {
      std::fill_n(row(k), stride, 0.0);
      std::fill_n(cold_row(k), cold_stride, 0.0);
    }
  }
  /// True when every double of contact k's whole row is zero (a fresh contact).
  [[nodiscard]] bool whole_row_is_zero(std::size_t k) const noexcept {
    const auto zero = [](double v) { return v == 0.0; };
    return std::all_of(row(k), row(k) + stride, zero) && std::all_of(cold_history.data() + k * cold_stride, cold_history.data() + (k + 1) * cold_stride, zero);
  }
  /// Moves contact `from`'s rows onto contact `to` (to <= from: compaction).
  void move_row(std::size_t from, std::size_t to) noexcept {
    std::copy_n(history.data() + from * stride, stride, row(to));
    std::copy_n(cold_history.data() + from * cold_stride, cold_stride, cold_row(to));
  }
};

/// Particle–facet candidates of one wall, sorted by particle then facet.
/// A group is the run of one particle's facets: the facet-selection rule
/// (wall_contacts.hpp) looks at a whole group.
struct WallContacts {
  std::vector<std::uint32_t> particle;
  std::vector<std::uint32_t> facet;
  std::vector<std::uint32_t> group_start;  ///< groups + 1 entries
  std::size_t stride = 0;
  std::vector<double> history;

  // Filled every step by the geometry pass.
  std::vector<std::array<double, 3>> weights;  ///< barycentric weights of the closest point
  std::vector<double> distance;                ///< m, centre to closest point
  std::vector<std::uint8_t> feature;           ///< TriangleFeature of the closest point
  std::vector<std::uint8_t> selected;          ///< 1: this facet carries the contact (edge/vertex duplicates are 0)

  [[nodiscard]] std::size_t size() const noexcept { return particle.size(); }
  [[nodiscard]] std::size_t group_count() const noexcept { return group_start.empty() ? 0 : group_start.size() - 1; }
  [[nodiscard]] double* row(std::size_t k) noexcept { return history.data() + k * stride; }
  /// Sets the lists from sorted (particle, facet) pairs; history zeroed.
  void assign(std::span<const std::pair<std::uint32_t, std::uint32_t>> candidates, std::size_t history_stride);
};

/// Per-contact results of the last force evaluation, pairs first, then each
/// wall's contacts at its offset.
struct ContactOutputs {
  std::vector<Vec3> force;   ///< N, on the first body (the particle for wall contacts)
  std::vector<Vec3> point;   ///< m, where it acts
  std::vector<Vec3> couple;  ///< N m, pure couple on the first body; empty unless a law has one
  /// m, periodic cell only (else empty): per pair contact, the image offset of
  /// the second particle, (x_first + branch) - x_second; zero inside the cell.
  std::vector<Vec3> shift;

  void resize(std::size_t n, bool with_couple, std::size_t periodic_pairs = 0);
};

/// Which pair outputs a force evaluation writes. `complete`: all of them, for
/// anything that reads the outputs after the step (measurements, results,
/// servos). `gathered_only`: only those of pairs whose loads the integrator
/// gathers (a body not marked in Incidence::direct); the others keep stale
/// values. The particle resultants are the same bits either way: storing
/// three or four vectors per contact that nobody reads cost about 5 % of a
/// step on the peer benchmark (docs/dem_benchmarks.md). Wall contacts are
/// always written.
enum class ContactRecord { complete, gathered_only };

/// For every particle the contacts it takes part in, in increasing contact
/// order. entry = contact << 1 | role, role 1 = the particle is the second body.
///
/// Split summation (why: a separate gather pass over all contacts cost a third
/// of a step). The pair loop runs over `pair_chunks` contiguous ranges of
/// contact indices (one per thread) and adds a contact's force straight into
/// a particle's resultant when its range is the first range that touches the
/// particle: those contacts are a prefix of the particle's list, added in
/// increasing order. The rest of the list (from gather_from[i]: pairs in later
/// ranges, then the wall contacts) is gathered afterwards, continuing the same
/// sum. A particle receives direct additions from one range only, so the
/// ranges run in parallel without races, and every particle sums the same
/// terms in the same order for any number of ranges: bit-identical results.
struct Incidence {
  std::vector<std::uint32_t> start;  ///< particles + 1
  std::vector<std::uint32_t> entry;
  std::vector<std::size_t> chunk_start;    ///< pair_chunks + 1 contact indices bounding the pair loop's ranges
  std::vector<std::uint32_t> gather_from;  ///< per particle: its first entry not added by the pair loop
  /// Per pair contact: direct_first | direct_second, the bodies the pair loop adds it to.
  std::vector<std::uint8_t> direct;
  static constexpr std::uint8_t direct_first = 1;
  static constexpr std::uint8_t direct_second = 2;

  [[nodiscard]] std::size_t pair_chunks() const noexcept { return chunk_start.empty() ? 0 : chunk_start.size() - 1; }
};

/// `wall_offsets[w]` is where wall w's contacts start in ContactOutputs;
/// `pair_chunks` (>= 1) the number of ranges the pair loop is split into.
[[nodiscard]] Incidence build_incidence(std::size_t particle_count, const PairContacts& pairs, std::span<const WallContacts* const> walls,
                                        std::span<const std::size_t> wall_offsets, std::size_t pair_chunks);

/// History rows keyed by two stable integers ((id, id) for pairs, (id, facet)
/// for wall contacts), kept across a neighbour-list rebuild.
class HistoryArchive {
 public:
  using Key = std::array<std::int64_t, 2>;
  explicit HistoryArchive(std::size_t stride) : stride_(stride) {}
  /// Room for `rows` add()s: the arrays are not reallocated (and copied) as
  /// they grow. Pages of the room no row uses are never touched, so an upper
  /// bound costs address space, not memory (the paper model's generated body:
  /// 2.1 million rows of 184 B, 0.4 GB, which doubling growth held twice over
  /// while it copied them).
  void reserve(std::size_t rows) {
    keys_.reserve(rows);
    rows_.reserve(rows * stride_);
  }
  /// The archive of keys[k] -> row k of `rows` (keys.size() rows of
  /// `stride`), taking the rows instead of copying them; the same archive as
  /// add() of each row in order, then seal() (all-zero rows dropped).
  [[nodiscard]] static HistoryArchive adopt(std::size_t stride, std::vector<Key> keys, std::vector<double> rows);
  /// Rows that are all zero are fresh contacts and are not kept.
  void add(Key key, const double* row);
  /// Keeps the entries whose key `keep(key)` accepts, in insertion order,
  /// compacted in place and sealed: the archive add() of those entries would
  /// give, without holding the rows twice (the paper model's 0.4 GB).
  template <class Keep>
  void retain(Keep&& keep) {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < keys_.size(); ++k) {
      if (!keep(keys_[k])) continue;
      if (kept != k) {  // kept < k: each row moves down onto one already moved or dropped
        keys_[kept] = keys_[k];
        std::copy_n(rows_.begin() + std::ptrdiff_t(k * stride_), stride_, rows_.begin() + std::ptrdiff_t(kept * stride_));
      }
      ++kept;
    }
    keys_.resize(kept);
    rows_.resize(kept * stride_);
    seal();
  }
  /// Sorts the keys; call once after the last add().
  void seal();
  /// The row stored under `key`, or nullptr.
  [[nodiscard]] const double* find(Key key) const;
  [[nodiscard]] std::size_t size() const noexcept { return keys_.size(); }
  [[nodiscard]] std::size_t stride() const noexcept { return stride_; }
  /// Entry k in insertion order.
  [[nodiscard]] const Key& key(std::size_t k) const noexcept { return keys_[k]; }
  [[nodiscard]] const double* row(std::size_t k) const noexcept { return rows_.data() + k * stride_; }
  /// Keys, in increasing order, whose row is non-zero in `column` (e.g. the
  /// bond state: pairs that stay candidates however far apart they move).
  [[nodiscard]] std::vector<Key> keys_with_nonzero(std::size_t column) const;

 private:
  std::size_t stride_;
  std::vector<Key> keys_;
  std::vector<double> rows_;
  std::vector<std::uint32_t> sorted_;
};

/// match_previous_pairs: a pair of the new lists with no pair before it.
inline constexpr std::uint32_t no_previous_pair = 0xffffffffu;

/// The inverse of a re-sort (ParticleStore::permute): old slot -> new slot, on `threads` threads.
[[nodiscard]] std::vector<std::uint32_t> inverse_order(std::span<const std::uint32_t> new_to_old, int threads);

/// Carrying history across a rebuild of the same particles, re-sorted by slot
/// (`old_to_new`: the inverse_order of ParticleStore::permute's order): for each new pair (first[k],
/// second[k], slots after the re-sort), the index of the pair of `before`
/// (slots before it) that joins the same two particles in the same order, or
/// no_previous_pair. The rows an id-keyed HistoryArchive would restore, found
/// without copying them out and back, sorting keys or searching (a rebuild of
/// the paper's open pile spent 5 s on that: 2.6 million rows of 184 B).
[[nodiscard]] std::vector<std::uint32_t> match_previous_pairs(const PairContacts& before, std::span<const std::uint32_t> old_to_new,
                                                              const std::vector<std::uint32_t>& first, const std::vector<std::uint32_t>& second,
                                                              int threads);

/// Writes every row k of `pairs` (sized, its rows not yet written): row
/// match[k] of `before`, or zeros where match[k] is no_previous_pair; then
/// empties `before`. Its history is given back to the kernel 2 MiB at a time
/// as soon as no row still to be written reads it (release_whole_units), so
/// the old and the new history do not both exist whole: the rows of a
/// model at rest come in nearly the same order after a rebuild, and the
/// paper model's peak memory lost 0.4 GB (docs/dem_benchmarks.md, Memory).
void move_matched_rows(PairContacts&& before, const std::vector<std::uint32_t>& match, PairContacts& pairs, int threads);

[[nodiscard]] HistoryArchive archive_history(const PairContacts& pairs, const ParticleStore& particles);
[[nodiscard]] HistoryArchive archive_history(const WallContacts& contacts, const ParticleStore& particles);
/// Writes every row of `pairs` (sized, its rows not yet written): the archived
/// row of the same two particles, or zeros.
void restore_history(PairContacts& pairs, const ParticleStore& particles, const HistoryArchive& archive, int threads);
/// Copies archived rows into the matching contacts of the new lists (others stay zero).
void restore_history(WallContacts& contacts, const ParticleStore& particles, const HistoryArchive& archive, int threads);

}  // namespace dfc::dem
