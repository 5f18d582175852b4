#include "core/exact_sum.hpp"

#include <limits>

namespace frac {
namespace {
__extension__ typedef unsigned __int128 uint128;  // (GCC's and Clang's: the top three digits with room)
}  // namespace

void ExactSum::add_special(double x) {
  if (std::isnan(x))
    ++nan_;
  else if (x > 0)
    ++plus_inf_;
  else
    ++minus_inf_;
}

void ExactSum::settle() {
  for (std::size_t k = 0; k + 1 < kDigits; ++k) {
    const std::int64_t carry = digits_[k] >> 32;  // (floor: the digit left in [0, 2^32))
    digits_[k] -= carry * (std::int64_t{1} << 32);
    digits_[k + 1] += carry;
  }
  pending_ = 0;
}

void ExactSum::add(const ExactSum& other) {
  ExactSum settled = other;
  settled.settle();
  settle();
  for (std::size_t k = 0; k < kDigits; ++k) digits_[k] += settled.digits_[k];
  nan_ += other.nan_;
  plus_inf_ += other.plus_inf_;
  minus_inf_ += other.minus_inf_;
}

std::array<std::int64_t, ExactSum::kWords> ExactSum::words() const {
  ExactSum settled = *this;
  settled.settle();
  std::array<std::int64_t, kWords> out{};
  for (std::size_t k = 0; k < kDigits; ++k) out[k] = settled.digits_[k];
  out[kDigits] = nan_;
  out[kDigits + 1] = plus_inf_;
  out[kDigits + 2] = minus_inf_;
  return out;
}

ExactSum ExactSum::from_words(std::span<const std::int64_t, kWords> words) {
  ExactSum s;
  for (std::size_t k = 0; k < kDigits; ++k) s.digits_[k] = words[k];
  s.nan_ = words[kDigits];
  s.plus_inf_ = words[kDigits + 1];
  s.minus_inf_ = words[kDigits + 2];
  s.settle();
  return s;
}

double ExactSum::value() const {
  if (nan_ > 0 || (plus_inf_ > 0 && minus_inf_ > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (plus_inf_ > 0) return std::numeric_limits<double>::infinity();
  if (minus_inf_ > 0) return -std::numeric_limits<double>::infinity();
  ExactSum m = *this;
  m.settle();
  const bool negative = m.digits_[kDigits - 1] < 0;
  if (negative) {
    for (std::int64_t& d : m.digits_) d = -d;
    m.settle();
  }
  std::size_t top = kDigits;
  while (top > 0 && m.digits_[top - 1] == 0) --top;
  if (top == 0) return 0.0;
  // The top three digits as an integer B (at most 96 bits) times 2^scale, and whether any digit below is not 0.
  const std::size_t high = top - 1, low = high >= 2 ? high - 2 : 0;
  uint128 b = 0;
  for (std::size_t k = high + 1; k-- > low;) b = (b << 32) | static_cast<std::uint64_t>(m.digits_[k]);
  bool sticky = false;
  for (std::size_t k = 0; k < low; ++k) sticky = sticky || m.digits_[k] != 0;
  const int scale = 32 * static_cast<int>(low) - 1074;
  const auto top64 = static_cast<std::uint64_t>(b >> 64), low64 = static_cast<std::uint64_t>(b);
  const int bits = top64 != 0 ? 128 - std::countl_zero(top64) : 64 - std::countl_zero(low64);
  // The lowest bit a double keeps: 53 bits below the leading one, or 2^-1074 (subnormal).
  const int lowest = std::max(scale + bits - 53, -1074);
  const int shift = lowest - scale;
  double r;
  if (shift <= 0) {  // exact: B < 2^53
    r = std::ldexp(static_cast<double>(static_cast<std::uint64_t>(b)), scale);
  } else {
    const uint128 one = 1;
    auto kept = static_cast<std::uint64_t>(b >> shift);
    const uint128 rest = b & ((one << shift) - 1), half = one << (shift - 1);
    if (rest > half || (rest == half && (sticky || (kept & 1) != 0))) ++kept;
    r = std::ldexp(static_cast<double>(kept), lowest);  // (2^53 at most: exact; past the largest double: inf)
  }
  return negative ? -r : r;
}

double sum_of(std::span<const ExactSum> parts) {
  ExactSum sum;
  for (const ExactSum& p : parts) sum.add(p);
  return sum.value();
}

}  // namespace frac
