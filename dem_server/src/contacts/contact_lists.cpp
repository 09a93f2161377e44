#include "dfc/dem/contact_lists.hpp"

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "dfc/dem/huge_pages.hpp"
#include "dfc/dem/parallel.hpp"

namespace dfc::dem {

void WallContacts::assign(std::span<const std::pair<std::uint32_t, std::uint32_t>> candidates, std::size_t history_stride) {
  const std::size_t n = candidates.size();
  particle.resize(n);
  facet.resize(n);
  group_start.clear();
  for (std::size_t k = 0; k < n; ++k) {
    particle[k] = candidates[k].first;
    facet[k] = candidates[k].second;
    if (k == 0 || particle[k] != particle[k - 1]) group_start.push_back(std::uint32_t(k));
  }
  group_start.push_back(std::uint32_t(n));
  stride = history_stride;
  history.assign(n * stride, 0.0);
  weights.assign(n, {});
  distance.assign(n, 0.0);
  feature.assign(n, 0);
  selected.assign(n, 0);
}

void ContactOutputs::resize(std::size_t n, bool with_couple, std::size_t periodic_pairs) {
  force.assign(n, Vec3{});
  point.assign(n, Vec3{});
  couple.assign(with_couple ? n : 0, Vec3{});
  shift.assign(periodic_pairs, Vec3{});
}

Incidence build_incidence(std::size_t particle_count, const PairContacts& pairs, std::span<const WallContacts* const> walls,
                          std::span<const std::size_t> wall_offsets, std::size_t pair_chunks) {
  Incidence inc;
  inc.start.assign(particle_count + 1, 0);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    ++inc.start[pairs.first[k] + 1];
    ++inc.start[pairs.second[k] + 1];
  }
  for (const WallContacts* w : walls)
    for (const auto p : w->particle) ++inc.start[p + 1];
  for (std::size_t i = 0; i < particle_count; ++i) inc.start[i + 1] += inc.start[i];
  inc.entry.resize(inc.start.back());
  std::vector<std::uint32_t> fill(inc.start.begin(), inc.start.end() - 1);
  // Filled in increasing contact index: each particle's list is in a fixed order.
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    inc.entry[fill[pairs.first[k]]++] = std::uint32_t(k << 1);
    inc.entry[fill[pairs.second[k]]++] = std::uint32_t(k << 1 | 1u);
  }
  // The pair loop's ranges; a particle's entries in the first range touching
  // it (its owner) are added there, the prefix of its list up to gather_from.
  const std::size_t chunks = std::max<std::size_t>(pair_chunks, 1);
  inc.chunk_start.resize(chunks + 1);
  for (std::size_t c = 0; c <= chunks; ++c) inc.chunk_start[c] = pairs.size() * c / chunks;
  constexpr std::size_t no_owner = ~std::size_t{0};
  std::vector<std::size_t> owner(particle_count, no_owner);
  inc.gather_from.assign(inc.start.begin(), inc.start.end() - 1);
  inc.direct.assign(pairs.size(), 0);
  for (std::size_t c = 0; c < chunks; ++c)
    for (std::size_t k = inc.chunk_start[c]; k < inc.chunk_start[c + 1]; ++k)
      for (const auto& [i, bit] : {std::pair{pairs.first[k], Incidence::direct_first}, std::pair{pairs.second[k], Incidence::direct_second}}) {
        if (owner[i] == no_owner) owner[i] = c;
        if (owner[i] != c) continue;
        inc.direct[k] |= bit;
        ++inc.gather_from[i];
      }
  for (std::size_t w = 0; w < walls.size(); ++w)
    for (std::size_t k = 0; k < walls[w]->size(); ++k)
      inc.entry[fill[walls[w]->particle[k]]++] = std::uint32_t((wall_offsets[w] + k) << 1);
  return inc;
}

HistoryArchive HistoryArchive::adopt(std::size_t stride, std::vector<Key> keys, std::vector<double> rows) {
  if (rows.size() != keys.size() * stride) throw std::logic_error("HistoryArchive::adopt: rows are not keys.size() x stride");
  HistoryArchive archive(stride);
  // Compacted in place, in order: row k moves to slot kept <= k.
  std::size_t kept = 0;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const double* row = rows.data() + k * stride;
    if (std::all_of(row, row + stride, [](double v) { return v == 0.0; })) continue;
    if (kept != k) {
      std::copy_n(row, stride, rows.data() + kept * stride);
      keys[kept] = keys[k];
    }
    ++kept;
  }
  keys.resize(kept);
  rows.resize(kept * stride);
  archive.keys_ = std::move(keys);
  archive.rows_ = std::move(rows);
  archive.seal();
  return archive;
}

void HistoryArchive::add(Key key, const double* row) {
  if (std::all_of(row, row + stride_, [](double v) { return v == 0.0; })) return;
  keys_.push_back(key);
  rows_.insert(rows_.end(), row, row + stride_);
}

void HistoryArchive::seal() {
  sorted_.resize(keys_.size());
  std::iota(sorted_.begin(), sorted_.end(), 0u);
  std::sort(sorted_.begin(), sorted_.end(), [&](std::uint32_t a, std::uint32_t b) { return keys_[a] < keys_[b]; });
}

const double* HistoryArchive::find(Key key) const {
  const auto it = std::lower_bound(sorted_.begin(), sorted_.end(), key, [&](std::uint32_t a, const Key& k) { return keys_[a] < k; });
  if (it == sorted_.end() || keys_[*it] != key) return nullptr;
  return rows_.data() + std::size_t(*it) * stride_;
}

std::vector<HistoryArchive::Key> HistoryArchive::keys_with_nonzero(std::size_t column) const {
  std::vector<Key> out;
  if (column >= stride_) return out;
  for (const std::uint32_t k : sorted_)
    if (rows_[std::size_t(k) * stride_ + column] != 0.0) out.push_back(keys_[k]);
  return out;
}

std::vector<std::uint32_t> inverse_order(std::span<const std::uint32_t> new_to_old, int threads) {
  std::vector<std::uint32_t> old_to_new(new_to_old.size());
  const auto n = std::int64_t(new_to_old.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t s = 0; s < n; ++s) old_to_new[new_to_old[std::size_t(s)]] = std::uint32_t(s);
  return old_to_new;
}

std::vector<std::uint32_t> match_previous_pairs(const PairContacts& before, std::span<const std::uint32_t> old_to_new,
                                                const std::vector<std::uint32_t>& first, const std::vector<std::uint32_t>& second, int threads) {
  const std::size_t n = old_to_new.size();
  // The previous pairs by their first particle's new slot: (second's new slot, index).
  std::vector<std::uint32_t> start(n + 1, 0);
  for (const std::uint32_t i : before.first) ++start[old_to_new[i] + 1];
  for (std::size_t s = 0; s < n; ++s) start[s + 1] += start[s];
  std::vector<std::pair<std::uint32_t, std::uint32_t>> partner(before.size());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < before.size(); ++k)
    partner[fill[old_to_new[before.first[k]]]++] = {old_to_new[before.second[k]], std::uint32_t(k)};
  std::vector<std::uint32_t> match(first.size(), no_previous_pair);
  const auto count = static_cast<std::int64_t>(first.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(count >= min_parallel_items)
  for (std::int64_t k = 0; k < count; ++k) {
    const auto c = std::size_t(k);
    for (std::uint32_t e = start[first[c]]; e < start[first[c] + 1]; ++e)
      if (partner[e].first == second[c]) {
        match[c] = partner[e].second;
        break;
      }
  }
  return match;
}

namespace {

/// The rows of `pairs` in parts and blocks: the parts as a static loop over
/// the rows splits them (each thread first-touches the rows its part of the
/// pair loop reads), each part copied in blocks of about one 2 MiB unit.
struct RowBlocks {
  std::size_t rows = 0, parts = 1, block_rows = 1, blocks = 0;
  RowBlocks(std::size_t n, std::size_t row_bytes, int threads)
      : rows(n),
        parts(std::int64_t(n) >= min_parallel_items ? std::size_t(std::max(threads, 1)) : 1),
        block_rows(std::max<std::size_t>(1, huge_page_bytes / std::max<std::size_t>(row_bytes, 1))) {
    for (std::size_t t = 0; t < parts; ++t) blocks = std::max(blocks, (start(t + 1) - start(t) + block_rows - 1) / block_rows);
  }
  [[nodiscard]] std::size_t start(std::size_t part) const noexcept { return rows * part / parts; }
  /// Rows [first, last) of block b of part t.
  [[nodiscard]] std::pair<std::size_t, std::size_t> block(std::size_t t, std::size_t b) const noexcept {
    const std::size_t first = std::min(start(t) + b * block_rows, start(t + 1));
    return {first, std::min(first + block_rows, start(t + 1))};
  }
};

/// The whole 2 MiB units of an array (release_whole_units gives back only those).
struct WholeUnits {
  std::uintptr_t first = 0, end = 0;
  WholeUnits(const void* data, std::size_t bytes)
      : first((reinterpret_cast<std::uintptr_t>(data) + huge_page_bytes - 1) / huge_page_bytes),
        end((reinterpret_cast<std::uintptr_t>(data) + bytes) / huge_page_bytes) {}
  [[nodiscard]] std::size_t count() const noexcept { return end > first ? std::size_t(end - first) : 0; }
  /// Gives back units [from, to) of the count() (indices from first).
  void release(std::size_t from, std::size_t to) const noexcept {
    if (to > from) release_whole_units(reinterpret_cast<void*>((first + from) * huge_page_bytes), (to - from) * huge_page_bytes);
  }
};

void write_row(const double* from, std::size_t stride, double* row) noexcept {
  if (from) std::copy_n(from, stride, row);
  else std::fill_n(row, stride, 0.0);
}

/// The direct copy: block by block, each old unit given back after the block
/// in which its last reader was written (`done_after`, 0: no reader).
void copy_releasing_as_read(const double* before, std::size_t stride, const std::vector<std::uint32_t>& match, double* after, const RowBlocks& rows,
                            const WholeUnits& units, const std::vector<std::size_t>& done_after) {
  // The units in order of release: those given back after block b are unit_order[release[b] .. release[b + 1]).
  std::vector<std::size_t> release(rows.blocks + 2, 0), unit_order(units.count());
  for (const std::size_t b : done_after) ++release[b + 1];
  for (std::size_t b = 0; b + 1 < release.size(); ++b) release[b + 1] += release[b];
  std::vector<std::size_t> fill(release.begin(), release.end() - 1);
  for (std::size_t u = 0; u < units.count(); ++u) unit_order[fill[done_after[u]]++] = u;
  const auto release_after = [&](std::size_t b) {
    for (std::size_t e = release[b]; e < release[b + 1]; ++e) units.release(unit_order[e], unit_order[e] + 1);
  };
  release_after(0);
#pragma omp parallel num_threads(int(rows.parts))
  {
    const auto t = std::size_t(omp_get_thread_num());
    for (std::size_t b = 0; b < rows.blocks; ++b) {
      const auto [first, last] = rows.block(t, b);
      for (std::size_t k = first; k < last; ++k)
        write_row(match[k] == no_previous_pair ? nullptr : before + std::size_t(match[k]) * stride, stride, after + k * stride);
#pragma omp barrier
#pragma omp single
      release_after(b + 1);
    }
  }
}

/// The copy through a staging area, for an order far from the old one (the
/// first rebuild after a search to the bond gap sorted the particles by
/// larger cells): (1) the old rows in their own order into the staging area,
/// grouped by the block of the new rows that reads them, each old unit given
/// back once passed; (2) group by group into the new rows, each staged group
/// given back once written. At no time do the old and new rows both exist
/// whole; the price is a second copy.
void copy_through_staging(UninitialisedDoubles& before, std::size_t stride, std::size_t old_rows, const std::vector<std::uint32_t>& match, double* after,
                          const RowBlocks& rows, int threads) {
  const std::size_t groups = rows.parts * rows.blocks;
  const auto group_of = [&](std::size_t k) {  // part-major: the groups of part t are t * blocks ..
    const std::size_t t = std::min(rows.parts - 1, k * rows.parts / std::max<std::size_t>(rows.rows, 1));
    const std::size_t part = k < rows.start(t) ? t - 1 : k >= rows.start(t + 1) ? t + 1 : t;
    return part * rows.blocks + (k - rows.start(part)) / rows.block_rows;
  };
  std::vector<std::uint32_t> reader(old_rows, no_previous_pair);
  for (std::size_t k = 0; k < rows.rows; ++k)
    if (match[k] != no_previous_pair) reader[match[k]] = std::uint32_t(k);
  // (1) Per part of the old rows and group, the staged rows: their slots are then fixed whatever the thread count.
  const RowBlocks old_parts(old_rows, stride * sizeof(double), threads);
  std::vector<std::size_t> slot((old_parts.parts * groups) + 1, 0);
  for (std::size_t t = 0; t < old_parts.parts; ++t)
    for (std::size_t m = old_parts.start(t); m < old_parts.start(t + 1); ++m)
      if (reader[m] != no_previous_pair) ++slot[group_of(reader[m]) * old_parts.parts + t + 1];
  for (std::size_t e = 0; e + 1 < slot.size(); ++e) slot[e + 1] += slot[e];
  const std::vector<std::size_t> group_start = [&] {
    std::vector<std::size_t> out(groups + 1);
    for (std::size_t g = 0; g <= groups; ++g) out[g] = slot[g * old_parts.parts];
    return out;
  }();
  // Each staged row written once below, before it is read. Not on huge
  // pages: the first pass writes to every group at once, and a huge page
  // would make each group's whole 2 MiB resident at its first row.
  UninitialisedDoubles staged(group_start[groups] * stride);
  std::vector<std::uint32_t> staged_reader(group_start[groups]);
  const WholeUnits old_units(before.data(), before.size() * sizeof(double));
  const auto unit_of = [&](std::size_t m) {  // the whole unit that holds row m's start (0 before the first)
    const std::uintptr_t u = reinterpret_cast<std::uintptr_t>(before.data() + m * stride) / huge_page_bytes;
    return u > old_units.first ? std::size_t(u - old_units.first) : std::size_t(0);
  };
#pragma omp parallel num_threads(int(old_parts.parts))
  {
    const auto t = std::size_t(omp_get_thread_num());
    std::vector<std::size_t> fill(groups);
    for (std::size_t g = 0; g < groups; ++g) fill[g] = slot[g * old_parts.parts + t];
    const std::size_t first = old_parts.start(t), last = old_parts.start(t + 1);
    // This part's whole units, given back as the pass leaves each one (the shared ones at its ends stay).
    std::size_t released = first == 0 ? 0 : unit_of(first) + 1;
    for (std::size_t m = first; m < last; ++m) {
      if (reader[m] != no_previous_pair) {
        const std::size_t e = fill[group_of(reader[m])]++;
        std::copy_n(before.data() + m * stride, stride, staged.data() + e * stride);
        staged_reader[e] = reader[m];
      }
      if ((m & 1023) == 1023 && old_units.count() > 0) {
        const std::size_t passed = std::min(unit_of(m + 1), old_units.count());
        old_units.release(released, passed);
        released = std::max(released, passed);
      }
    }
  }
  before = UninitialisedDoubles{};
  // (2) Group by group (a part's groups on its thread, as the rows' first
  // touch wants), each thread giving back the staged units it has passed
  // (a part's groups are contiguous in the staging area).
  const WholeUnits staged_units(staged.data(), staged.size() * sizeof(double));
  const auto unit_at = [&](std::size_t e) {  // the whole unit that holds staged row e's start, clamped to the whole ones
    const std::uintptr_t u = reinterpret_cast<std::uintptr_t>(staged.data() + e * stride) / huge_page_bytes;
    return std::clamp(u, staged_units.first, std::max(staged_units.first, staged_units.end)) - staged_units.first;
  };
#pragma omp parallel num_threads(int(rows.parts))
  {
    const auto t = std::size_t(omp_get_thread_num());
    std::size_t released = t == 0 ? 0 : unit_at(group_start[t * rows.blocks]) + 1;  // the unit shared with the part before stays
    for (std::size_t b = 0; b < rows.blocks; ++b) {
      const std::size_t g = t * rows.blocks + b;
      for (std::size_t e = group_start[g]; e < group_start[g + 1]; ++e) write_row(staged.data() + e * stride, stride, after + staged_reader[e] * stride);
      const auto [first, last] = rows.block(t, b);
      for (std::size_t k = first; k < last; ++k)
        if (match[k] == no_previous_pair) write_row(nullptr, stride, after + k * stride);
      const std::size_t passed = unit_at(group_start[g + 1]);
      staged_units.release(released, passed);
      released = std::max(released, passed);
    }
  }
}

/// move_matched_rows for one of the two history arrays: `before` holds
/// `old_rows` rows of `stride`, `after` match.size() rows (sized, not written);
/// `before` is emptied.
void move_rows(UninitialisedDoubles& before, std::size_t stride, std::size_t old_rows, const std::vector<std::uint32_t>& match, UninitialisedDoubles& after,
               int threads) {
  if (stride == 0) return;
  const std::size_t row_bytes = stride * sizeof(double);
  const RowBlocks rows(match.size(), row_bytes, threads);
  // Per whole unit of the old history: after which block of the direct copy
  // no new row reads it any more (0: none reads it).
  const WholeUnits units(before.data(), before.size() * sizeof(double));
  std::vector<std::size_t> done_after(units.count(), 0);
  for (std::size_t t = 0; t < rows.parts && units.count() > 0 && row_bytes > 0; ++t)
    for (std::size_t k = rows.start(t); k < rows.start(t + 1); ++k) {
      if (match[k] == no_previous_pair) continue;
      const std::size_t block = (k - rows.start(t)) / rows.block_rows + 1;
      const auto row = reinterpret_cast<std::uintptr_t>(before.data() + std::size_t(match[k]) * stride);
      for (std::uintptr_t u = std::max(row / huge_page_bytes, units.first); u <= (row + row_bytes - 1) / huge_page_bytes && u < units.end; ++u)
        done_after[u - units.first] = std::max(done_after[u - units.first], block);
    }
  // What the direct copy would hold beyond the old rows at its worst: the new
  // rows written less the old units given back, after each block. Where it
  // would hold more than a quarter of the old rows, the rows go through the staging area.
  std::vector<double> given_back(rows.blocks + 1, 0.0);
  for (const std::size_t b : done_after) given_back[b] += double(huge_page_bytes);
  double released = 0.0, worst = 0.0;
  for (std::size_t b = 0; b <= rows.blocks; ++b) {
    released += given_back[b];
    const double written = double(std::min(b * rows.block_rows, rows.rows / rows.parts + 1) * rows.parts * row_bytes);
    worst = std::max(worst, written - released);
  }
  if (worst > 0.25 * double(before.size() * sizeof(double))) copy_through_staging(before, stride, old_rows, match, after.data(), rows, threads);
  else copy_releasing_as_read(before.data(), stride, match, after.data(), rows, units, done_after);
  before = UninitialisedDoubles{};
}

}  // namespace

void move_matched_rows(PairContacts&& before, const std::vector<std::uint32_t>& match, PairContacts& pairs, int threads) {
  // The hot rows first: their old array is given back before the cold one is copied.
  move_rows(before.history, pairs.stride, before.size(), match, pairs.history, threads);
  move_rows(before.cold_history, pairs.cold_stride, before.size(), match, pairs.cold_history, threads);
  before = PairContacts{};
}

void PairContacts::resize_history() {
  reserve_with_huge_pages(history, size() * stride);
  history.resize(size() * stride);
  reserve_with_huge_pages(cold_history, size() * cold_stride);
  cold_history.resize(size() * cold_stride);
}

HistoryArchive archive_history(const PairContacts& pairs, const ParticleStore& particles) {
  HistoryArchive archive(pairs.whole_stride());
  if (pairs.whole_stride() == 0) return archive;
  archive.reserve(pairs.size());
  std::vector<double> whole(pairs.whole_stride());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    pairs.copy_whole_row(k, whole.data());
    archive.add({particles.id[pairs.first[k]], particles.id[pairs.second[k]]}, whole.data());
  }
  archive.seal();
  return archive;
}

HistoryArchive archive_history(const WallContacts& contacts, const ParticleStore& particles) {
  HistoryArchive archive(contacts.stride);
  if (contacts.stride == 0) return archive;
  for (std::size_t k = 0; k < contacts.size(); ++k)
    archive.add({particles.id[contacts.particle[k]], std::int64_t(contacts.facet[k])}, contacts.history.data() + k * contacts.stride);
  archive.seal();
  return archive;
}

void restore_history(PairContacts& pairs, const ParticleStore& particles, const HistoryArchive& archive, int threads) {
  if (pairs.whole_stride() == 0) return;
  const bool archived = archive.size() > 0;
  const auto n = static_cast<std::int64_t>(pairs.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto c = std::size_t(k);
    pairs.set_whole_row(c, archived ? archive.find({particles.id[pairs.first[c]], particles.id[pairs.second[c]]}) : nullptr);
  }
}

void restore_history(WallContacts& contacts, const ParticleStore& particles, const HistoryArchive& archive, int threads) {
  if (contacts.stride == 0 || archive.size() == 0) return;
  const auto n = static_cast<std::int64_t>(contacts.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto c = std::size_t(k);
    if (const double* row = archive.find({particles.id[contacts.particle[c]], std::int64_t(contacts.facet[c])}))
      std::copy(row, row + contacts.stride, contacts.row(c));
  }
}

}  // namespace dfc::dem
