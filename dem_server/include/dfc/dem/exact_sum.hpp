#pragma once
// ExactSum: the sum of doubles kept exactly, rounded once when read, so that
// it does not depend on the order of the terms nor on how they were split
// into partial sums. Why: a decomposed run (issue "Beyond one machine")
// sums the forces on a wall, the interface loads and the monitors over the
// particles of every process; a floating-point sum in any fixed order still
// depends on which process held which term, an exact one does not, so 1 and
// N processes (and any thread count) give the same bits.
//
// The method is the long accumulator of Kulisch & Miranker (1986), in the
// "small superaccumulator" form of Neal (2015, "Fast exact summation using
// small and large superaccumulators", arXiv:1505.05571, §3): a fixed-point
// integer covering the whole double range, 2 098 bits from 2^-1074, held in
// signed 64-bit limbs of 32 bits each. A term adds its signed 53-bit
// significand, shifted into place, as a low part in [0, 2^32) to one limb
// and the rest to the next; the spare bits of every limb absorb 512 terms
// before the carries are propagated (about 4 ns a term here). Reading
// rounds the exact value to the nearest double, ties to even (subnormal
// results may round twice; no force or energy of a run comes near them).
// Infinities and NaN follow IEEE addition: +inf and -inf together give NaN.
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "dfc/dem/parallel.hpp"
#include "dfc/dem/vec3.hpp"

namespace dfc::dem {

class ExactSum {
 public:
  static constexpr int kLimbBits = 32;
  static constexpr std::uint64_t kLimbMask = 0xffffffffULL;
  /// Terms before the carries must be propagated: a term adds less than 2^32
  /// to one limb and less than 2^53 in magnitude to the next, so 2^9 of them
  /// keep every limb below 2^62 in magnitude.
  static constexpr std::int64_t kTermsPerCarry = 512;
  static constexpr int kLimbs = 68;  ///< bits 2^-1074 to 2^1023 (2 098) in 66 limbs, 2 more for overflow and carries

  ExactSum() = default;
  explicit ExactSum(double x) { add(x); }

  void add(double x) noexcept {  // inline: it is the whole cost of a sum (about 30 instructions)
    const auto bits = std::bit_cast<std::uint64_t>(x);
    const int biased_exponent = int((bits >> 52) & 0x7ff);
    if (biased_exponent == 0x7ff) return add_special(x);  // inf or NaN
    std::uint64_t significand = bits & ((std::uint64_t(1) << 52) - 1);
    // x = significand 2^(position - 1074): a subnormal at 2^-1074, a normal
    // number with its hidden bit at 2^(biased - 1075).
    int position = 0;
    if (biased_exponent != 0) {
      significand |= std::uint64_t(1) << 52;
      position = biased_exponent - 1;
    } else if (significand == 0) {
      return;  // +-0
    }
    const auto negative = std::int64_t(bits >> 63);
    const std::int64_t m = (std::int64_t(significand) ^ -negative) + negative;  // the signed significand
    const int k = position >> 5, shift = position & 31;
    // m 2^shift = low + high 2^32 exactly, with low in [0, 2^32) (two's
    // complement) and high the floor of the rest (arithmetic shift).
    const auto low = std::int64_t((std::uint64_t(m) << shift) & kLimbMask);
    const std::int64_t high = shift == 0 ? m >> 32 : m >> (32 - shift);
    limb_[std::size_t(k)] += low;
    limb_[std::size_t(k + 1)] += high;
    if (++terms_since_carry_ >= kTermsPerCarry) propagate_carries();
  }
  ExactSum& operator+=(double x) noexcept {
    add(x);
    return *this;
  }
  /// Adds another accumulator (a partial sum from another thread or process).
  ExactSum& operator+=(const ExactSum& other) noexcept;

  /// The exact sum rounded to the nearest double (ties to even).
  [[nodiscard]] double value() const noexcept;

  /// The limbs after carry propagation, then the counts of +inf and -inf
  /// terms and whether a NaN was added: equal sums have equal limbs, and the
  /// element-wise sum of two accumulators' limbs is their sum's (an MPI_SUM
  /// reduction of them is exact).
  [[nodiscard]] std::array<std::int64_t, kLimbs + 3> normalised_limbs() const noexcept;
  /// The accumulator of normalised_limbs() (or of a sum of them).
  [[nodiscard]] static ExactSum from_limbs(const std::array<std::int64_t, kLimbs + 3>& limbs) noexcept;

 private:
  void add_special(double x) noexcept;
  void propagate_carries() noexcept;

  std::array<std::int64_t, kLimbs> limb_{};
  std::int64_t terms_since_carry_ = 0;
  std::int64_t infinities_ = 0;  ///< +inf terms (kept apart from the finite sum)
  std::int64_t negative_infinities_ = 0;
  bool nan_ = false;
};

/// Three exact sums: a force or a moment.
struct ExactVec3Sum {
  ExactSum x, y, z;
  void add(const Vec3& v) noexcept {
    x.add(v.x);
    y.add(v.y);
    z.add(v.z);
  }
  ExactVec3Sum& operator+=(const ExactVec3Sum& other) noexcept {
    x += other.x;
    y += other.y;
    z += other.z;
    return *this;
  }
  [[nodiscard]] Vec3 value() const noexcept { return {x.value(), y.value(), z.value()}; }
};

/// The exact sums of N quantities over the items i in [0, n), unrounded:
/// terms(i) returns their N terms. On `threads` threads, each summing its
/// items into its own accumulators, merged at the end: exact, so the same
/// bits for any thread count and (under MPI, merged by their limbs) any split
/// of the items among processes. Integers (counts) below 2^53 are summed
/// exactly as doubles too.
template <std::size_t N, class Terms>
[[nodiscard]] std::array<ExactSum, N> exact_accumulators(std::size_t n, int threads, const Terms& terms) {
  std::vector<std::array<ExactSum, N>> partial;
  const auto count = std::int64_t(n);
#pragma omp parallel num_threads(threads) if(count >= min_parallel_items)
  {
    std::array<ExactSum, N> local{};
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < count; ++i) {
      const std::array<double, N> t = terms(std::size_t(i));
      for (std::size_t k = 0; k < N; ++k) local[k].add(t[k]);
    }
#pragma omp critical(dfc_exact_sums)
    partial.push_back(local);  // any order: the merge is exact
  }
  std::array<ExactSum, N> total{};
  for (const auto& p : partial)
    for (std::size_t k = 0; k < N; ++k) total[k] += p[k];
  return total;
}

/// exact_accumulators, each rounded once.
template <std::size_t N, class Terms>
[[nodiscard]] std::array<double, N> exact_sums(std::size_t n, int threads, const Terms& terms) {
  const std::array<ExactSum, N> total = exact_accumulators<N>(n, threads, terms);
  std::array<double, N> values{};
  for (std::size_t k = 0; k < N; ++k) values[k] = total[k].value();
  return values;
}

/// exact_sums of a vector quantity.
template <class Term>
[[nodiscard]] Vec3 exact_vec3_sum(std::size_t n, int threads, const Term& term) {
  const auto s = exact_sums<3>(n, threads, [&](std::size_t i) {
    const Vec3 v = term(i);
    return std::array<double, 3>{v.x, v.y, v.z};
  });
  return {s[0], s[1], s[2]};
}

}  // namespace dfc::dem
