#pragma once
// sin and cos of every joint angle at once. Private to comply_model.
//
// Why not std::sin/std::cos: seven libm calls were a tenth of a microsecond of the cycle, each a
// call with branches on the argument's size; this loop has no call and no branch, so the compiler
// vectorises it over the joints. Accuracy: Cody-Waite reduction by pi/2 in three parts (the
// constants of fdlibm's __ieee754_rem_pio2: pi/2 split into 33-bit pieces, so k * piece is exact
// for |k| < 2^20), then Taylor polynomials on |r| <= pi/4 whose truncation errors, below
// (pi/4)^19 / 19! ~ 1e-19, are far under rounding: results within a few ulp of libm. Beyond
// |q| = 1e5 rad (a continuous joint wound up for days) the reduction would lose bits, and the
// caller uses libm instead.

#include <cmath>

namespace comply::model {

inline constexpr double kFastTrigLimit = 1e5;

/// s[i] = sin(q[i]), c[i] = cos(q[i]) for i < count; every |q[i]| <= kFastTrigLimit.
inline void jointSinCos(const double* q, int count, double* s, double* c) noexcept {
  constexpr double kTwoOverPi = 0.6366197723675814;
  constexpr double kPiOver2Part1 = 0x1.921fb54400000p+0;
  constexpr double kPiOver2Part2 = 0x1.0b4611a600000p-34;
  constexpr double kPiOver2Part3 = 0x1.3198a2e037073p-69;
  constexpr double kRoundingShift = 0x1.8p52;  // adding it rounds to an integer, branch-free
  for (int i = 0; i < count; ++i) {
    const double k = (q[i] * kTwoOverPi + kRoundingShift) - kRoundingShift;
    const double r = ((q[i] - k * kPiOver2Part1) - k * kPiOver2Part2) - k * kPiOver2Part3;
    const double r2 = r * r;
    // sin r = r (1 - r^2/3! + r^4/5! - ... - r^16/17!), cos r = 1 - r^2/2! + ... + r^18/18!.
    const double sin_r =
        r +
        r * r2 *
            (-1.0 / 6 +
             r2 * (1.0 / 120 +
                   r2 * (-1.0 / 5040 +
                         r2 * (1.0 / 362880 + r2 * (-1.0 / 39916800 +
                                                    r2 * (1.0 / 6227020800 +
                                                          r2 * (-1.0 / 1307674368000 +
                                                                r2 * (1.0 / 355687428096000))))))));
    const double cos_r =
        1.0 +
        r2 * (-0.5 +
              r2 * (1.0 / 24 +
                    r2 * (-1.0 / 720 +
                          r2 * (1.0 / 40320 +
                                r2 * (-1.0 / 3628800 +
                                      r2 * (1.0 / 479001600 +
                                            r2 * (-1.0 / 87178291200 +
                                                  r2 * (1.0 / 20922789888000 +
                                                        r2 * (-1.0 / 6402373705728000)))))))));
    // Quadrant k mod 4: (sin, cos) = (s, c), (c, -s), (-s, -c), (-c, s).
    const auto quadrant = static_cast<long long>(k) & 3;
    const bool swap = (quadrant & 1) != 0;
    const double sin_sign = (quadrant & 2) != 0 ? -1.0 : 1.0;
    const double cos_sign = ((quadrant + 1) & 2) != 0 ? -1.0 : 1.0;
    s[i] = sin_sign * (swap ? cos_r : sin_r);
    c[i] = cos_sign * (swap ? sin_r : cos_r);
  }
}

}  // namespace comply::model
