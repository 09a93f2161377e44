#pragma once
// Random numbers that are the same on every platform and standard library:
// std::mt19937_64 is specified bit for bit by the standard, the std::
// distributions are not, so the conversion to doubles is written out here.
#include <cstdint>
#include <random>

namespace dfc::dem {

class PortableRandom {
 public:
  explicit PortableRandom(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1): the top 53 bits of one draw, scaled by 2^-53.
  double uniform() { return double(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace dfc::dem
