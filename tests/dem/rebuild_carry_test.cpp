// Carrying pair history across a neighbour-list rebuild by slot
// (match_previous_pairs) finds exactly the rows the id-keyed HistoryArchive
// restores, and a bond that the search no longer finds is kept either way.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <numeric>
#include <random>
#include <set>
#include <string>

#include "dem_test_support.hpp"
#include "dfc/dem/contact_lists.hpp"
#include "dfc/dem/huge_pages.hpp"

namespace dfc::dem {
namespace {

TEST(RebuildCarry, MatchesWhatTheIdKeyedArchiveRestores) {
  // 400 particles with scattered ids; 3 000 previous pairs oriented by id,
  // a third of their rows zero (fresh contacts, which the archive drops);
  // the particles re-sorted by a random permutation; the new lists keep two
  // thirds of the old pairs (some listed the other way round, as a pair
  // whose ids are not in order would be) and add new ones.
  std::mt19937_64 random(11);
  ParticleStore before_store;
  std::vector<std::int64_t> ids(400);
  std::iota(ids.begin(), ids.end(), 0);
  std::shuffle(ids.begin(), ids.end(), random);
  for (const std::int64_t id : ids) before_store.add_sphere(1000 + 7 * id, {}, 1e-3, 2650);
  const std::size_t n = before_store.size();
  PairContacts before;
  before.stride = 4;
  std::uniform_int_distribution<std::uint32_t> slot(0, std::uint32_t(n - 1));
  std::set<std::pair<std::uint32_t, std::uint32_t>> used;
  while (before.size() < 3000) {
    std::uint32_t a = slot(random), b = slot(random);
    if (a == b) continue;
    if (before_store.id[a] > before_store.id[b]) std::swap(a, b);
    if (!used.insert({a, b}).second) continue;
    before.first.push_back(a);
    before.second.push_back(b);
    for (int c = 0; c < 4; ++c) before.history.push_back(before.size() % 3 == 0 ? 0.0 : double(before.size()) + 0.25 * c);
  }
  const HistoryArchive archive = archive_history(before, before_store);

  std::vector<std::uint32_t> new_to_old(n);
  std::iota(new_to_old.begin(), new_to_old.end(), 0u);
  std::shuffle(new_to_old.begin(), new_to_old.end(), random);
  ParticleStore after_store = before_store;
  after_store.permute(new_to_old);
  std::vector<std::uint32_t> old_to_new(n);
  for (std::size_t s = 0; s < n; ++s) old_to_new[new_to_old[s]] = std::uint32_t(s);
  std::vector<std::uint32_t> first, second;
  for (std::size_t k = 0; k < before.size(); ++k) {
    if (k % 3 == 1) continue;  // no longer a candidate
    const bool reversed = k % 7 == 0;
    first.push_back(old_to_new[reversed ? before.second[k] : before.first[k]]);
    second.push_back(old_to_new[reversed ? before.first[k] : before.second[k]]);
  }
  for (int extra = 0; extra < 500; ++extra) {
    const std::uint32_t a = slot(random), b = slot(random);
    if (a != b && !used.contains({new_to_old[a], new_to_old[b]}) && !used.contains({new_to_old[b], new_to_old[a]})) {
      first.push_back(a);
      second.push_back(b);
    }
  }
  std::vector<std::size_t> shuffled(first.size());
  std::iota(shuffled.begin(), shuffled.end(), 0u);
  std::shuffle(shuffled.begin(), shuffled.end(), random);

  for (const int threads : {1, 2}) {
    const std::vector<std::uint32_t> match = match_previous_pairs(before, old_to_new, first, second, threads);
    ASSERT_EQ(match.size(), first.size());
    std::size_t carried = 0, fresh = 0;
    for (std::size_t k = 0; k < first.size(); ++k) {
      const double* expected = archive.find({after_store.id[first[k]], after_store.id[second[k]]});
      if (match[k] == no_previous_pair) {
        EXPECT_EQ(expected, nullptr) << "pair " << k;
        ++fresh;
        continue;
      }
      // The same two particles in the same order, and the row the archive holds (or a zero row it dropped).
      EXPECT_EQ(new_to_old[first[k]], before.first[match[k]]);
      EXPECT_EQ(new_to_old[second[k]], before.second[match[k]]);
      const double* row = before.history.data() + match[k] * before.stride;
      if (expected == nullptr) EXPECT_TRUE(std::all_of(row, row + before.stride, [](double v) { return v == 0.0; }));
      else EXPECT_TRUE(std::equal(row, row + before.stride, expected));
      ++carried;
    }
    // Two thirds carried less the reversed ones (1 in 7), the rest fresh: both kinds occur.
    EXPECT_GT(carried, 1500u);
    EXPECT_GT(fresh, 400u);

    PairContacts copied;
    copied.first = first;
    copied.second = second;
    copied.stride = before.stride;
    copied.history.assign(first.size() * copied.stride, 0.0);
    move_matched_rows(PairContacts(before), match, copied, threads);
    PairContacts restored = copied;
    std::fill(restored.history.begin(), restored.history.end(), 0.0);
    restore_history(restored, after_store, archive, threads);
    EXPECT_EQ(copied.history, restored.history);
  }
}

TEST(RebuildCarry, ABondPulledBeyondTheSearchKeepsItsRowThroughManyRebuilds) {
  // Two bonded spheres separating at 0.2 m/s with a 1 um skin: each rebuild
  // (every 25 steps or so) no longer finds the pair, which is carried by slot as a
  // persistent bond; its history must match a run that rebuilds once only.
  const auto law = make_contact_law({{"law", "linear_pbond"}, {"emod_pa", 1e6}, {"pb_emod_pa", 1e6}, {"pb_ten_pa", 1e12},
                                     {"pb_coh_pa", 1e12}, {"bond_gap_m", 1e-4}});
  const auto run = [&](double skin) {
    Simulation sim(SimulationSettings{.particle_law = law, .gravity = {}, .local_damping = 0.0, .skin = skin, .threads = 1});
    sim.add_sphere(7, {0, 0, 0}, 1e-3, 2650);
    sim.add_sphere(3, {0, 0, 2e-3 + 5e-5}, 1e-3, 2650);
    ParticleStore& p = sim.particles_for_edit();
    for (std::size_t i = 0; i < p.size(); ++i) p.velocity[i] = {0, 0, p.id[i] == 3 ? 0.2 : -0.2};
    sim.run(400, 1e-7);
    return sim;
  };
  const Simulation often = run(1e-6), once = run(1.0);
  EXPECT_GE(often.rebuild_count(), 10u);  // measured 15
  EXPECT_EQ(once.rebuild_count(), 1u);
  EXPECT_EQ(often.bond_counts().intact, 1);
  ASSERT_EQ(often.pair_contacts().size(), 1u);
  EXPECT_EQ(often.pair_contacts().history, once.pair_contacts().history);
  for (std::size_t i = 0; i < 2; ++i) {  // by id: the two runs may sort the slots differently
    for (std::size_t j = 0; j < 2; ++j) {
      if (often.particles().id[i] == once.particles().id[j]) {
        EXPECT_EQ(often.particles().position[i], once.particles().position[j]);
      }
    }
  }
}

TEST(RebuildCarry, AdvisingHugePagesKeepsTheContents) {
  std::vector<double> v{1.0, 2.0, 3.0};
  reserve_with_huge_pages(v, std::size_t(1) << 20);  // 8 MiB: whole 2 MiB pages inside
  EXPECT_GE(v.capacity(), std::size_t(1) << 20);
  EXPECT_EQ(v, (std::vector<double>{1.0, 2.0, 3.0}));
  v.assign(std::size_t(1) << 20, 0.5);
  EXPECT_EQ(v[12345], 0.5);
}

/// Bytes of a /proc/self/status field ("VmRSS", "VmHWM"), or -1 where there is none.
double status_bytes(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind(field + ":", 0) == 0) return 1024.0 * std::stod(line.substr(field.size() + 1));
  return -1.0;
}

// Under AddressSanitizer the resident set holds its quarantine of freed blocks
// and their shadow memory as well, so the peak says nothing about the move
// (seen: 1.03 times the bound, now and then): the rows are checked, the peak not.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool peak_is_measurable = false;
#else
constexpr bool peak_is_measurable = true;
#endif

/// move_matched_rows of `before` by `match` on 1, 2 and 3 threads: every row
/// where it belongs, and the peak memory of the move below `peak_fraction`
/// of the new rows above what was resident before it.
void expect_moved_rows(const PairContacts& before, const std::vector<std::uint32_t>& match, double peak_fraction) {
  const std::size_t stride = before.stride;
  for (const int threads : {1, 2, 3}) {
    PairContacts pairs;
    pairs.stride = stride;
    pairs.history.resize(match.size() * stride);
    PairContacts consumed = before;
    // The peak from here on (Linux: writing 5 to clear_refs resets VmHWM to VmRSS).
    std::ofstream clear_refs("/proc/self/clear_refs");
    clear_refs << "5";
    clear_refs.close();
    const bool peak_reset = !clear_refs.fail();
    const double resident = status_bytes("VmRSS");
    move_matched_rows(std::move(consumed), match, pairs, threads);
    const double peak = status_bytes("VmHWM");
    EXPECT_TRUE(consumed.history.empty());
    for (std::size_t k = 0; k < match.size(); ++k) {
      const double* row = pairs.row(k);
      const bool as_expected = match[k] == no_previous_pair ? std::all_of(row, row + stride, [](double v) { return v == 0.0; })
                                                           : std::equal(row, row + stride, before.history.data() + std::size_t(match[k]) * stride);
      ASSERT_TRUE(as_expected) << "row " << k << ", " << threads << " threads";
    }
    if (peak_is_measurable && peak_reset && resident > 0.0 && peak > 0.0) {
      EXPECT_LT(peak - resident, peak_fraction * double(match.size() * stride * sizeof(double))) << threads << " threads";
    }
  }
}

/// 200 000 rows of 23 doubles (37 MB, 17 whole 2 MiB units), every value
/// non-zero, so that a row read after its unit was given back (it reads
/// zeros) shows.
PairContacts large_history() {
  constexpr std::size_t rows = 200000, stride = 23;
  PairContacts before;
  before.stride = stride;
  before.first.assign(rows, 0);
  before.second.assign(rows, 1);
  before.history.resize(rows * stride);
  for (std::size_t k = 0; k < rows * stride; ++k) before.history[k] = 1.0 + double(k);
  return before;
}

/// The old rows 0 .. rows-1 in order, every 13th gone, a fresh row (no_previous_pair) before every 17th.
std::vector<std::uint32_t> old_order_with_gaps(std::size_t rows) {
  std::vector<std::uint32_t> match;
  for (std::size_t k = 0; k < rows; ++k) {
    if (k % 13 == 5) continue;
    if (k % 17 == 3) match.push_back(no_previous_pair);
    match.push_back(std::uint32_t(k));
  }
  return match;
}

TEST(RebuildCarry, MovingRowsInNearlyTheirOldOrderGivesBackTheOldHistoryAsTheyAreRead) {
  // The new lists: the old order with every 13th pair gone, a fresh pair
  // every 17th, rows swapped a few hundred places apart, and three rows taken
  // from the far end (each pins its unit until it is read).
  const PairContacts before = large_history();
  std::vector<std::uint32_t> match = old_order_with_gaps(before.size());
  for (std::size_t k = 0; k + 300 < match.size(); k += 1000) std::swap(match[k], match[k + 300]);
  for (const std::size_t k : {1000, 50000, 120000}) {
    const auto it = std::find(match.begin() + std::ptrdiff_t(k) + 1, match.end(), std::uint32_t(before.size() - 1 - k / 100));
    if (match[k] != no_previous_pair && it != match.end()) std::swap(match[k], *it);
  }
  // Copied whole, the new history (39 MB) would add itself to the peak;
  // given back as the copy passes, the old units leave about as fast as the
  // new ones arrive: the peak exceeds the start by a block a thread (2 MiB
  // each) and the three units the far rows pin, about 12 MB with three threads.
  expect_moved_rows(before, match, 0.75);
}

TEST(RebuildCarry, MovingRowsInAnOrderFarFromTheOldOneGoesThroughAStagingAreaAndHoldsTheRowsOnce) {
  // The new lists: the old rows shuffled, every 13th gone, a fresh row every
  // 17th: read in this order no old unit could be given back before the end.
  const PairContacts before = large_history();
  std::vector<std::uint32_t> match = old_order_with_gaps(before.size());
  std::mt19937_64 random(5);
  std::shuffle(match.begin(), match.end(), random);
  // Staged, the old units leave as the first pass reads them and the staged
  // ones as the second writes them: the peak exceeds the start by the
  // partial units and the index arrays (a few MB), not by the new rows.
  expect_moved_rows(before, match, 0.75);
}

}  // namespace
}  // namespace dfc::dem
