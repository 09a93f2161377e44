// ExactSum (exact_sum.hpp): the exact sum of doubles, rounded once; the same
// bits in any order and any split into partial sums.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "dfc/dem/exact_sum.hpp"
#include "dfc/dem/portable_random.hpp"

namespace dfc::dem {
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

double exact(const std::vector<double>& terms) {
  ExactSum sum;
  for (double t : terms) sum.add(t);
  return sum.value();
}

/// Terms over 40 decades with both signs, and some that cancel exactly.
std::vector<double> wide_terms(std::size_t n, std::uint64_t seed) {
  PortableRandom random(seed);
  std::vector<double> terms;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = (random.uniform() < 0.5 ? -1.0 : 1.0) * std::pow(10.0, random.uniform(-20.0, 20.0));
    terms.push_back(t);
    if (i % 7 == 0) terms.push_back(-t);
  }
  return terms;
}

TEST(ExactSum, CancellationThatAPlainSumLosesIsKept) {
  EXPECT_EQ(exact({1e300, 1.0, -1e300}), 1.0);  // a plain sum gives 0
  EXPECT_EQ(exact({1.0, 1e100, 1.0, -1e100}), 2.0);
  // The three doubles nearest 0.1, 0.2 and 0.3 sum exactly to 2^-55; left to
  // right, 0.1 + 0.2 rounds up first and leaves 2^-54.
  EXPECT_EQ(exact({0.1, 0.2, -0.3}), std::ldexp(1.0, -55));
  EXPECT_EQ(0.1 + 0.2 - 0.3, std::ldexp(1.0, -54));
}

TEST(ExactSum, RoundsOnceToNearestTiesToEven) {
  const double big = std::ldexp(1.0, 53);
  // 2^53 + 1 + 1 is 2^53 + 2, a double; left to right each +1 is a tie rounded back to 2^53.
  EXPECT_EQ(exact({big, 1.0, 1.0}), big + 2.0);
  EXPECT_EQ((big + 1.0) + 1.0, big);
  // 1 + 2^-53 is a tie: to even, 1; any further bit below breaks the tie upwards.
  EXPECT_EQ(exact({1.0, std::ldexp(1.0, -53)}), 1.0);
  EXPECT_EQ(exact({1.0, std::ldexp(1.0, -53), std::ldexp(1.0, -300)}), 1.0 + std::ldexp(1.0, -52));
  EXPECT_EQ(exact({-1.0, -std::ldexp(1.0, -53), -std::ldexp(1.0, -300)}), -1.0 - std::ldexp(1.0, -52));
  // (1 + 2^-52) + 2^-53 is a tie with an odd last bit: up, to 1 + 2^-51.
  EXPECT_EQ(exact({1.0 + std::ldexp(1.0, -52), std::ldexp(1.0, -53)}), 1.0 + std::ldexp(1.0, -51));
}

TEST(ExactSum, TwoTermsGiveTheHardwaresCorrectlyRoundedSum) {
  // IEEE addition of two doubles is the exact sum rounded once to nearest,
  // ties to even: the reference for the rounding, over exponents 60 apart
  // at most (partial overlap, ties, cancellation) and equal magnitudes.
  PortableRandom random(21);
  for (int i = 0; i < 200000; ++i) {
    const double a = (random.uniform() < 0.5 ? -1.0 : 1.0) * std::ldexp(1.0 + random.uniform(), int(random.uniform(-40.0, 40.0)));
    double b = (random.uniform() < 0.5 ? -1.0 : 1.0) * std::ldexp(1.0 + random.uniform(), int(random.uniform(-40.0, 40.0)));
    if (i % 3 == 0) b = -a * (1.0 + std::ldexp(double(int(random.uniform(-8.0, 8.0))), -52));  // near cancellation
    ASSERT_TRUE(same_bits(exact({a, b}), a + b)) << a << " + " << b;
  }
}

TEST(ExactSum, TheSameBitsInAnyOrderAndAnySplit) {
  const std::vector<double> terms = wide_terms(5000, 3);
  const double forward = exact(terms);
  const double backward = exact(std::vector<double>(terms.rbegin(), terms.rend()));
  EXPECT_TRUE(same_bits(forward, backward));
  // A plain sum of the same terms depends on the order (the check can fail).
  double plain_forward = 0.0, plain_backward = 0.0;
  for (double t : terms) plain_forward += t;
  for (auto t = terms.rbegin(); t != terms.rend(); ++t) plain_backward += *t;
  EXPECT_FALSE(same_bits(plain_forward, plain_backward));
  // Split among 1 to 7 "processes" by a stride, merged in any order, also through the limbs.
  for (std::size_t parts = 1; parts <= 7; ++parts) {
    std::vector<ExactSum> partial(parts);
    for (std::size_t i = 0; i < terms.size(); ++i) partial[(i * 31) % parts].add(terms[i]);
    ExactSum merged;
    for (std::size_t p = parts; p-- > 0;) merged += partial[p];
    EXPECT_TRUE(same_bits(merged.value(), forward)) << parts << " parts";
    auto limbs = partial[0].normalised_limbs();
    for (std::size_t p = 1; p < parts; ++p) {
      const auto more = partial[p].normalised_limbs();
      for (std::size_t k = 0; k < limbs.size(); ++k) limbs[k] += more[k];  // as MPI_SUM adds them
    }
    EXPECT_TRUE(same_bits(ExactSum::from_limbs(limbs).value(), forward)) << parts << " parts, through the limbs";
  }
}

TEST(ExactSums, EveryThreadCountGivesTheBitsOfOneAccumulator) {
  // The monitors' sums (measure, momentum, the damping total) on every
  // thread: partial accumulators per thread, merged exactly.
  const std::vector<double> v = wide_terms(20000, 11);
  ASSERT_GE(std::int64_t(v.size()), min_parallel_items);  // the loop does run in parallel
  const double one = exact(v);
  for (const int threads : {1, 2, 3, 7}) {
    const auto s = exact_sums<2>(v.size(), threads, [&](std::size_t i) { return std::array<double, 2>{v[i], -2.0 * v[i]}; });
    EXPECT_TRUE(same_bits(s[0], one)) << threads << " threads";
    EXPECT_TRUE(same_bits(s[1], -2.0 * one)) << threads << " threads";  // exact sums scale exactly by powers of 2
    const Vec3 w = exact_vec3_sum(v.size(), threads, [&](std::size_t i) { return Vec3{v[i], 0.0, 1.0}; });
    EXPECT_TRUE(same_bits(w.x, one));
    EXPECT_EQ(w.z, double(v.size()));  // counts are exact
  }
  EXPECT_EQ(exact_sums<1>(0, 4, [](std::size_t) { return std::array<double, 1>{1.0}; })[0], 0.0);
}

TEST(ExactSum, AgreesWithAPlainSumWhereThatIsExact) {
  // Integers below 2^53 and binary fractions: every partial sum is a double.
  PortableRandom random(9);
  ExactSum sum;
  double plain = 0.0;
  for (int i = 0; i < 10000; ++i) {
    const double t = std::ldexp(std::floor(random.uniform(-1e6, 1e6)), -10);
    sum.add(t);
    plain += t;
  }
  EXPECT_EQ(sum.value(), plain);
}

TEST(ExactSum, ExtremesAndSpecials) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  const double huge = std::numeric_limits<double>::max();
  EXPECT_EQ(ExactSum().value(), 0.0);
  EXPECT_EQ(exact({tiny, tiny, tiny}), 3.0 * tiny);
  EXPECT_EQ(exact({huge, -huge, tiny}), tiny);
  EXPECT_EQ(exact({huge, huge, -huge}), huge);  // no overflow in between
  EXPECT_EQ(exact({huge, huge}), std::numeric_limits<double>::infinity());
  EXPECT_EQ(exact({-huge, -huge}), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(exact({1.0, std::numeric_limits<double>::infinity()}), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(exact({std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()})));
  EXPECT_TRUE(std::isnan(exact({1.0, std::numeric_limits<double>::quiet_NaN()})));
}

TEST(ExactSum, CarriesAndBorrowsRunThroughTheLimbs) {
  // Doubling a sum 60 times carries every limb's bits upwards (2^60 times a
  // significand of 53 ones); subtracting the smaller part back borrows
  // downwards through the limbs to its lowest bit.
  const double ones = std::ldexp(1.0, 53) - 1.0;  // all 53 significand bits set
  ExactSum sum(ones * std::ldexp(1.0, -600));
  for (int i = 0; i < 60; ++i) sum += sum;
  EXPECT_EQ(sum.value(), ones * std::ldexp(1.0, -540));
  sum.add(-std::ldexp(1.0, -540 + 52));  // the top bit off: 52 ones remain
  EXPECT_EQ(sum.value(), (std::ldexp(1.0, 52) - 1.0) * std::ldexp(1.0, -540));
  ExactSum negative(-ones);
  for (int i = 0; i < 60; ++i) negative += negative;
  negative.add(std::ldexp(1.0, -1000));  // far below: rounds away, but is held exactly
  EXPECT_EQ(negative.value(), -ones * std::ldexp(1.0, 60));
  negative.add(ones * std::ldexp(1.0, 60));
  EXPECT_EQ(negative.value(), std::ldexp(1.0, -1000));
}

}  // namespace
}  // namespace dfc::dem
