#pragma once
// 6x6 matrices as six columns of eight lanes (lanes 6 and 7 zero), for the per-cycle double
// diagonalisation. Private to comply_core.
//
// Why not Eigen: at 6x6, Eigen's fixed-size product does not fill a vector register per column
// (6 is not a multiple of the packet size) and measured 30 ns per product here, against 11 ns
// for the six broadcast-and-add steps below. GCC's vector extension lets the compiler pick the
// instructions (one AVX-512 register per column, or two AVX ones). Every access is a whole
// column, or a lane read: writing single lanes in memory and reading the column back as a vector
// defeats store-to-load forwarding, which cost more than the arithmetic in a first version.

#include <Eigen/Core>

namespace comply::lanes {

using Lanes = double __attribute__((vector_size(64)));
using LaneIndex = long long __attribute__((vector_size(64)));

struct Matrix {
  Lanes col[6];
};

/// Lane i of the result is lane index[i] of v. GCC's shuffle takes the index as a vector;
/// clang's takes only literal lanes, so there the lanes are gathered one by one (the fuzz and
/// analysis builds, where speed does not matter).
[[gnu::always_inline]] inline Lanes permute(Lanes v, LaneIndex index) noexcept {
#if defined(__clang__)
  Lanes result = {};
  for (int i = 0; i < 8; ++i) {
    result[i] = v[index[i]];
  }
  return result;
#else
  return __builtin_shuffle(v, index);
#endif
}

inline Matrix load(const Eigen::Matrix<double, 6, 6>& m) noexcept {
  Matrix result;
  for (int c = 0; c < 6; ++c) {
    result.col[c] = Lanes{m(0, c), m(1, c), m(2, c), m(3, c), m(4, c), m(5, c), 0.0, 0.0};
  }
  return result;
}

inline Matrix loadTransposed(const Eigen::Matrix<double, 6, 6>& m) noexcept {
  Matrix result;
  for (int c = 0; c < 6; ++c) {
    result.col[c] = Lanes{m(c, 0), m(c, 1), m(c, 2), m(c, 3), m(c, 4), m(c, 5), 0.0, 0.0};
  }
  return result;
}

inline void store(const Matrix& m, Eigen::Matrix<double, 6, 6>& out) noexcept {
  for (int c = 0; c < 6; ++c) {
    for (int r = 0; r < 6; ++r) {
      out(r, c) = m.col[c][r];
    }
  }
}

inline Matrix transpose(const Matrix& m) noexcept {
  Matrix result;
  for (int c = 0; c < 6; ++c) {
    result.col[c] = Lanes{m.col[0][c], m.col[1][c], m.col[2][c], m.col[3][c],
                          m.col[4][c], m.col[5][c], 0.0,         0.0};
  }
  return result;
}

/// a b, column by column: column j is the sum over k of a's column k times b(k, j).
inline Matrix product(const Matrix& a, const Matrix& b) noexcept {
  Matrix result;
  for (int j = 0; j < 6; ++j) {
    // Two partial sums: halves the dependency chain of the additions.
    Lanes even = a.col[0] * b.col[j][0] + a.col[2] * b.col[j][2] + a.col[4] * b.col[j][4];
    Lanes odd = a.col[1] * b.col[j][1] + a.col[3] * b.col[j][3] + a.col[5] * b.col[j][5];
    result.col[j] = even + odd;
  }
  return result;
}

/// a diag(d) b.
inline Matrix scaledProduct(const Matrix& a, const Lanes& d, const Matrix& b) noexcept {
  Matrix scaled;
  for (int k = 0; k < 6; ++k) {
    scaled.col[k] = a.col[k] * d[k];
  }
  return product(scaled, b);
}

}  // namespace comply::lanes
