#pragma once
// The exact sum of doubles, rounded once: a long fixed-point accumulator covering every double's range
// (2^-1074 to 2^1024 and carries above), in 32-bit digits held in 64-bit words, so that adding a double is three
// integer additions and carries wait until a read. Its value is the correctly rounded (to nearest, ties to even)
// exact sum of what was added, whatever the order, the grouping, the number of threads that added parts or the
// number of processes whose accumulators were merged (digit by digit, as integers: MPI_SUM of the digits). This is
// what makes a global sum the same bits on any number of ranks, where a sum in a fixed order would need every
// term on one process. Costs about 2 ns a term; 560 bytes an accumulator.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>

namespace frac {

class ExactSum {
 public:
  // 32-bit digits from 2^-1074 up: 2046 exponent offsets + 53 mantissa bits + 3 digits of carries.
  static constexpr std::size_t kDigits = 70;

  void add(double x) {
    if (!std::isfinite(x)) [[unlikely]] {
      add_special(x);
      return;
    }
    const auto bits = std::bit_cast<std::uint64_t>(x);
    const auto biased = static_cast<unsigned>((bits >> 52) & 0x7ff);
    std::uint64_t mantissa = bits & ((std::uint64_t{1} << 52) - 1);
    if (biased != 0) mantissa |= std::uint64_t{1} << 52;
    if (mantissa == 0) return;
    // x = ±mantissa · 2^(offset − 1074), offset = max(biased, 1) − 1.
    const unsigned offset = (biased == 0 ? 1u : biased) - 1;
    const unsigned digit = offset / 32;
    // mantissa · 2^r (at most 84 bits) as three digits.
    const unsigned r = offset % 32;
    const auto d0 = static_cast<std::int64_t>((mantissa << r) & 0xffffffffu);
    const auto d1 = static_cast<std::int64_t>((mantissa >> (32 - r)) & 0xffffffffu);
    const auto d2 = static_cast<std::int64_t>(r == 0 ? 0 : mantissa >> (64 - r));
    if (bits >> 63) {
      digits_[digit] -= d0;
      digits_[digit + 1] -= d1;
      digits_[digit + 2] -= d2;
    } else {
      digits_[digit] += d0;
      digits_[digit + 1] += d1;
      digits_[digit + 2] += d2;
    }
    // Each digit moves by less than 2^32 an addition: carries are settled before 2^30 of them can add up.
    if (++pending_ == kSettleEvery) [[unlikely]]
      settle();
  }

  // Adds another accumulator (a thread's or a process's part).
  void add(const ExactSum& other);

  // The correctly rounded sum (NaN if a NaN, or both infinities, were added; ±inf if one was, or if the sum
  // overflows). An exact zero is +0.
  double value() const;

  // The digits with carries settled (each in [0, 2^32), the last signed) and the counts of NaNs, +inf and −inf
  // (the last three words): what a process sends to merge sums with MPI_SUM over int64 words. Merging at most
  // 2^30 such arrays digit by digit cannot overflow; from_words reads a merged array back.
  static constexpr std::size_t kWords = kDigits + 3;
  std::array<std::int64_t, kWords> words() const;
  static ExactSum from_words(std::span<const std::int64_t, kWords> words);

 private:
  static constexpr int kSettleEvery = 1 << 30;
  void add_special(double x);
  void settle();  // carries up: every digit but the last in [0, 2^32)
  std::array<std::int64_t, kDigits> digits_{};
  std::int64_t nan_ = 0, plus_inf_ = 0, minus_inf_ = 0;
  int pending_ = 0;
};

// The value of the exact sum of several accumulators (the parts of a team's threads).
double sum_of(std::span<const ExactSum> parts);

}  // namespace frac
