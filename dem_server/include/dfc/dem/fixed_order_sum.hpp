#pragma once
// Sums over particles in an order fixed by the item count alone, computed on
// every thread: the local-damping total, summed every step (the monitors of
// an advance are exact sums, exact_sum.hpp, at 2-4 times the cost a term).
// Why: summed serially, the monitors were the largest serial part of the
// paper model's run after the rebuild (docs/dem_benchmarks.md, "Serial
// fraction"); an OpenMP reduction would make the last bits depend on the
// thread count (CONTRIBUTING.md §11). Not independent of how the items are
// split between processes: a decomposed run needs an exact sum here too
// (docs/determinism.md). Blocks of fixed_sum_block items are each
// summed in index order, then the block sums in block order: the association
// depends on n alone, so every thread count gives the same bits. A body of at
// most fixed_sum_block items is one block, summed as a plain loop.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dfc/dem/parallel.hpp"

namespace dfc::dem {

/// Items per block: its partial sum is a few doubles, so the block sums cost
/// nothing beside the terms; 4096 gives the paper model's 550 000 particles 135
/// blocks (balanced on 16 threads, still 2 a thread on 64).
inline constexpr std::size_t fixed_sum_block = 4096;

/// Sum of term(i) for i in [0, n) in the fixed blocked order. T is
/// value-initialised to zero and has +=.
template <class T, class Term>
[[nodiscard]] T fixed_order_sum(std::size_t n, int threads, const Term& term) {
  const std::size_t blocks = (n + fixed_sum_block - 1) / fixed_sum_block;
  std::vector<T> partial(blocks, T{});
  const auto block_count = std::int64_t(blocks);
#pragma omp parallel for schedule(static) num_threads(threads) if(std::int64_t(n) >= min_parallel_items)
  for (std::int64_t b = 0; b < block_count; ++b) {
    const std::size_t begin = std::size_t(b) * fixed_sum_block;
    const std::size_t end = begin + fixed_sum_block < n ? begin + fixed_sum_block : n;
    T sum{};
    for (std::size_t i = begin; i < end; ++i) sum += term(i);
    partial[std::size_t(b)] = sum;
  }
  T total{};
  for (const T& s : partial) total += s;
  return total;
}

}  // namespace dfc::dem
