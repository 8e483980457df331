// The values a fuzz target puts where a number was: the ones that break readers (NaN, infinities,
// the largest and smallest doubles, zero, negative zero, the integer limits, off by one from the
// value that was there) more often than chance would pick them, and any other the bytes spell.
#pragma once

#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <limits>

namespace sffcal_fuzz {

/// A double in place of `current`.
inline double special_real(FuzzedDataProvider& bytes, double current) {
  using limits = std::numeric_limits<double>;
  switch (bytes.ConsumeIntegralInRange<int>(0, 17)) {
    case 0: return limits::quiet_NaN();
    case 1: return limits::infinity();
    case 2: return -limits::infinity();
    case 3: return 0.0;
    case 4: return -0.0;
    case 5: return -1.0;
    case 6: return limits::max();
    case 7: return -limits::max();
    case 8: return limits::denorm_min();
    case 9: return 1e300;
    case 10: return -current;
    case 11: return current * 2.0;
    case 12: return current + 1.0;
    case 13: return current - 1.0;
    case 14: return current * 1e6;
    case 15: return current * 1e-6;
    case 16: return 2147483648.0;
    default: return bytes.ConsumeFloatingPoint<double>();
  }
}

/// An integer in place of `current` (narrowed by the caller to the field's width).
inline std::int64_t special_integer(FuzzedDataProvider& bytes, std::int64_t current) {
  using limits = std::numeric_limits<std::int64_t>;
  switch (bytes.ConsumeIntegralInRange<int>(0, 13)) {
    case 0: return 0;
    case 1: return -1;
    case 2: return 1;
    case 3: return static_cast<std::int64_t>(static_cast<std::uint64_t>(current) + 1);  // wraps
    case 4: return static_cast<std::int64_t>(static_cast<std::uint64_t>(current) - 1);
    case 5: return current == limits::min() ? current : -current;
    case 6: return std::numeric_limits<std::int32_t>::max();
    case 7: return std::numeric_limits<std::int32_t>::min();
    case 8: return limits::max();
    case 9: return limits::min();
    case 10: return std::int64_t{1} << 31;
    case 11: return std::int64_t{1} << 32;
    case 12: return bytes.ConsumeIntegralInRange<std::int64_t>(-64, 64);
    default: return bytes.ConsumeIntegral<std::int64_t>();
  }
}

}  // namespace sffcal_fuzz
