// fixed_order_sum: the damping total, summed every step, runs on every thread
// yet gives the same bits for any thread count, and a body of one block keeps
// the bits of a plain loop.
#include "dfc/dem/fixed_order_sum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "dfc/dem/vec3.hpp"

namespace dfc::dem {
namespace {

/// Terms spanning twelve orders of magnitude with both signs, so that any
/// other association of the sum changes its last bits.
std::vector<double> wide_terms(std::size_t n) {
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> exponent(-6.0, 6.0), sign(-1.0, 1.0);
  std::vector<double> v(n);
  for (double& x : v) x = (sign(rng) < 0 ? -1.0 : 1.0) * std::pow(10.0, exponent(rng));
  return v;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(FixedOrderSum, EveryThreadCountGivesTheBitsOfTheBlockedOrder) {
  const std::size_t n = 5 * fixed_sum_block + 123;  // several blocks and a short last one, above min_parallel_items
  const std::vector<double> v = wide_terms(n);
  // The blocked order written out: each block in index order, then the blocks in order.
  double blocked = 0.0;
  for (std::size_t begin = 0; begin < n; begin += fixed_sum_block) {
    double block = 0.0;
    for (std::size_t i = begin; i < std::min(n, begin + fixed_sum_block); ++i) block += v[i];
    blocked += block;
  }
  double plain = 0.0;
  for (const double x : v) plain += x;
  ASSERT_FALSE(same_bits(blocked, plain)) << "the terms must tell the two orders apart, else the test below proves nothing";
  for (const int threads : {1, 2, 3, 7}) {
    const double sum = fixed_order_sum<double>(n, threads, [&](std::size_t i) { return v[i]; });
    EXPECT_TRUE(same_bits(sum, blocked)) << threads << " threads";
  }
}

TEST(FixedOrderSum, OneBlockIsThePlainLoop) {
  const std::vector<double> v = wide_terms(fixed_sum_block);
  Vec3 plain;
  for (std::size_t i = 0; i < v.size(); ++i) plain += Vec3{v[i], -2.0 * v[i], v[v.size() - 1 - i]};
  const Vec3 sum = fixed_order_sum<Vec3>(v.size(), 2, [&](std::size_t i) { return Vec3{v[i], -2.0 * v[i], v[v.size() - 1 - i]}; });
  EXPECT_TRUE(same_bits(sum.x, plain.x) && same_bits(sum.y, plain.y) && same_bits(sum.z, plain.z));
}

TEST(FixedOrderSum, NoItemsSumToZero) {
  EXPECT_EQ(fixed_order_sum<double>(0, 4, [](std::size_t) { return 1.0; }), 0.0);
}

}  // namespace
}  // namespace dfc::dem
