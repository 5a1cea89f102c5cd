#pragma once
// The curves a chunk is evaluated on (chunk_player.cpp): the cubic Hermite basis of a segment
// between two waypoints and the quintic that blends a new chunk in from the reference in force.
// Orientation segments use the SO(3) exponential and right Jacobian of comply/core/rotation.hpp.
// Real-time safe.

namespace comply::pipeline::curve {

/// The cubic Hermite basis at s in [0, 1] and its first and second derivatives in s: a value is
/// w[0] p0 + w[1] h m0 + w[2] p1 + w[3] h m1 for end values p0, p1 and end slopes m0, m1 per
/// unit time over a segment of length h.
struct HermiteWeights {
  double value[4];
  double first[4];
  double second[4];
};

inline HermiteWeights hermite(double s) noexcept {
  const double s2 = s * s;
  const double s3 = s2 * s;
  return {{2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2},
          {6 * s2 - 6 * s, 3 * s2 - 4 * s + 1, -6 * s2 + 6 * s, 3 * s2 - 2 * s},
          {12 * s - 6, 6 * s - 4, -12 * s + 6, 6 * s - 2}};
}

/// The quintic that takes an offset with value and slope (e0, de0) and no curvature at s = 0 to
/// zero with zero slope and curvature at s = 1: e(s) = e0 w[0] + T de0 w[1] for a blend of length
/// T. `fade` is 1 - w[0]: 0 at the start, 1 at the end, flat at both.
struct QuinticWeights {
  double value[2];
  double first[2];   ///< d/ds
  double second[2];  ///< d^2/ds^2
};

inline QuinticWeights quinticDecay(double s) noexcept {
  const double s2 = s * s;
  const double s3 = s2 * s;
  const double s4 = s3 * s;
  const double s5 = s4 * s;
  return {{1 - 10 * s3 + 15 * s4 - 6 * s5, s - 6 * s3 + 8 * s4 - 3 * s5},
          {-30 * s2 + 60 * s3 - 30 * s4, 1 - 18 * s2 + 32 * s3 - 15 * s4},
          {-60 * s + 180 * s2 - 120 * s3, -36 * s + 96 * s2 - 60 * s3}};
}

}  // namespace comply::pipeline::curve
