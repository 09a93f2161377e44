#include "dfc/dem/exact_sum.hpp"

#include <cmath>
#include <limits>

namespace dfc::dem {

void ExactSum::add_special(double x) noexcept {
  if (std::isnan(x)) nan_ = true;
  else if (x > 0.0) ++infinities_;
  else ++negative_infinities_;
}

void ExactSum::propagate_carries() noexcept {
  // Each limb to [0, 2^32), its excess (floor division, so negative limbs
  // borrow) carried up; the top limb keeps the sign.
  for (std::size_t i = 0; i + 1 < limb_.size(); ++i) {
    const std::int64_t carry = limb_[i] >> kLimbBits;  // arithmetic shift: floor(limb / 2^32)
    limb_[i] = std::int64_t(std::uint64_t(limb_[i]) & kLimbMask);
    limb_[i + 1] += carry;
  }
  terms_since_carry_ = 0;
}

ExactSum& ExactSum::operator+=(const ExactSum& other) noexcept {
  propagate_carries();
  const auto limbs = other.normalised_limbs();
  for (std::size_t i = 0; i < limb_.size(); ++i) limb_[i] += limbs[i];
  terms_since_carry_ = 1;  // every limb grew by less than 2^32: less than one term's worth
  infinities_ += other.infinities_;
  negative_infinities_ += other.negative_infinities_;
  nan_ = nan_ || other.nan_;
  return *this;
}

std::array<std::int64_t, ExactSum::kLimbs + 3> ExactSum::normalised_limbs() const noexcept {
  ExactSum copy = *this;
  copy.propagate_carries();
  std::array<std::int64_t, kLimbs + 3> limbs{};
  for (std::size_t i = 0; i < copy.limb_.size(); ++i) limbs[i] = copy.limb_[i];
  limbs[kLimbs] = infinities_;
  limbs[kLimbs + 1] = negative_infinities_;
  limbs[kLimbs + 2] = nan_ ? 1 : 0;
  return limbs;
}

ExactSum ExactSum::from_limbs(const std::array<std::int64_t, kLimbs + 3>& limbs) noexcept {
  ExactSum sum;
  for (std::size_t i = 0; i < sum.limb_.size(); ++i) sum.limb_[i] = limbs[i];
  sum.propagate_carries();  // a sum over P accumulators' limbs holds up to P 2^32 a limb
  sum.infinities_ = limbs[kLimbs];
  sum.negative_infinities_ = limbs[kLimbs + 1];
  sum.nan_ = limbs[kLimbs + 2] != 0;
  return sum;
}

double ExactSum::value() const noexcept {
  if (nan_ || (infinities_ > 0 && negative_infinities_ > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (infinities_ > 0) return std::numeric_limits<double>::infinity();
  if (negative_infinities_ > 0) return -std::numeric_limits<double>::infinity();
  ExactSum magnitude = *this;
  magnitude.propagate_carries();
  const bool negative = magnitude.limb_.back() < 0;
  if (negative) {
    for (auto& l : magnitude.limb_) l = -l;
    magnitude.propagate_carries();
  }
  int top = kLimbs - 1;
  while (top >= 0 && magnitude.limb_[std::size_t(top)] == 0) --top;
  if (top < 0) return 0.0;
  // 2^1024 and beyond (bit 2098 up; limb 66 starts at bit 2112): no double.
  const double overflow = negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  if (top >= 66) return overflow;
  const auto limb = [&](int i) { return i >= 0 && i < kLimbs ? std::uint64_t(magnitude.limb_[std::size_t(i)]) : std::uint64_t(0); };
  // The 64 bits from the highest set bit down, and whether any bit below them
  // is set (ORed into the lowest: with 11 bits below the 53 kept, that decides
  // a tie exactly as the whole tail would).
  const int highest = kLimbBits * top + (kLimbBits - 1 - std::countl_zero(std::uint32_t(limb(top))));
  if (highest >= 2098) return overflow;
  const int lowest = highest - 63;
  const int first = lowest >= 0 ? lowest / kLimbBits : -1 - (-lowest - 1) / kLimbBits;  // floor division
  const int offset = lowest - kLimbBits * first;
  const std::uint64_t pair = limb(first) | (limb(first + 1) << kLimbBits);
  std::uint64_t window = (pair >> offset) | (offset == 0 ? 0 : limb(first + 2) << (64 - offset));
  bool sticky = offset != 0 && (limb(first) & ((std::uint64_t(1) << offset) - 1)) != 0;
  for (int i = first - 1; i >= 0 && !sticky; --i) sticky = limb(i) != 0;
  if (sticky) window |= 1;
  const double rounded = std::ldexp(double(window), lowest - 1074);  // double(window): to nearest, ties to even
  return negative ? -rounded : rounded;
}

}  // namespace dfc::dem
