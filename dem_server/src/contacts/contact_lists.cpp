#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/parallel.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <utility>

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

std::vector<std::uint32_t> match_previous_pairs(const PairContacts& before, std::span<const std::uint32_t> new_to_old,
                                                const std::vector<std::uint32_t>& first, const std::vector<std::uint32_t>& second, int threads) {
  const std::size_t n = new_to_old.size();
  const std::vector<std::uint32_t> old_to_new = inverse_order(new_to_old, threads);
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

void copy_matched_rows(const PairContacts& before, const std::vector<std::uint32_t>& match, PairContacts& pairs, int threads) {
  const auto n = static_cast<std::int64_t>(match.size());
  const std::size_t stride = pairs.stride;
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t k = 0; k < n; ++k) {
    const std::uint32_t m = match[std::size_t(k)];
    double* row = pairs.row(std::size_t(k));
    if (m != no_previous_pair) std::copy_n(before.history.data() + std::size_t(m) * stride, stride, row);
    else std::fill_n(row, stride, 0.0);
  }
}

HistoryArchive archive_history(const PairContacts& pairs, const ParticleStore& particles) {
  HistoryArchive archive(pairs.stride);
  if (pairs.stride == 0) return archive;
  archive.reserve(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k)
    archive.add({particles.id[pairs.first[k]], particles.id[pairs.second[k]]}, pairs.history.data() + k * pairs.stride);
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
  if (pairs.stride == 0) return;
  const bool archived = archive.size() > 0;
  const auto n = static_cast<std::int64_t>(pairs.size());
#pragma omp parallel for schedule(static) num_threads(threads) if(n >= min_parallel_items)
  for (std::int64_t k = 0; k < n; ++k) {
    const auto c = std::size_t(k);
    const double* row = archived ? archive.find({particles.id[pairs.first[c]], particles.id[pairs.second[c]]}) : nullptr;
    if (row) std::copy(row, row + pairs.stride, pairs.row(c));
    else std::fill_n(pairs.row(c), pairs.stride, 0.0);
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
