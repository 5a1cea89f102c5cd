#include "comply/core/symmetric_eigen.hpp"

#include <algorithm>
#include <cmath>

#include "jacobi_tracking.hpp"

namespace comply {
namespace {

/// Modified Gram-Schmidt on the columns; a column that collapses is replaced by a unit vector
/// orthogonal to the others (never happens for a rotation product, but keeps the result valid).
void orthonormalise(Matrix6d& basis) noexcept {
  for (int j = 0; j < 6; ++j) {
    for (int attempt = 0; attempt < 7; ++attempt) {
      for (int k = 0; k < j; ++k) {
        basis.col(j) -= basis.col(k).dot(basis.col(j)) * basis.col(k);
      }
      const double norm = basis.col(j).norm();
      if (norm > 1e-6) {
        basis.col(j) /= norm;
        break;
      }
      basis.col(j) = Vector6d::Unit(attempt % 6);
    }
  }
}

// Round-robin ("circle method") order: each round is a perfect matching of the six indices, so
// its three rotations touch disjoint pivots and the processor overlaps their division and square
// root latencies, which bound a rotation far more than its few multiplications.
constexpr int kRounds[5][3][2] = {{{0, 1}, {2, 5}, {3, 4}},
                                  {{0, 2}, {1, 3}, {4, 5}},
                                  {{0, 3}, {2, 4}, {1, 5}},
                                  {{0, 4}, {3, 5}, {1, 2}},
                                  {{0, 5}, {1, 4}, {2, 3}}};

/// Lane i -> lane of its partner in each round (lanes 6 and 7 map to themselves).
constexpr lanes::LaneIndex kPartners[5] = {{1, 0, 5, 4, 3, 2, 6, 7},
                                           {2, 3, 0, 1, 5, 4, 6, 7},
                                           {3, 5, 4, 0, 2, 1, 6, 7},
                                           {4, 2, 1, 5, 0, 3, 6, 7},
                                           {5, 4, 3, 2, 1, 0, 6, 7}};

/// `first` on the first lane of pair k of round r, `second` on the second, 0 elsewhere. Built
/// from one initialiser: clang does not allow writing a lane in a constant expression.
constexpr lanes::Lanes pairMask(int r, int k, double first, double second) {
  const int p = kRounds[r][k][0];
  const int q = kRounds[r][k][1];
  const auto lane = [&](int i) { return i == p ? first : (i == q ? second : 0.0); };
  return lanes::Lanes{lane(0), lane(1), lane(2), lane(3), lane(4), lane(5), lane(6), lane(7)};
}

/// 1 on the lanes of pair k of round r.
constexpr lanes::Lanes pairLanes(int r, int k) {
  return pairMask(r, k, 1.0, 1.0);
}

/// -1 on the first lane of pair k of round r, +1 on the second.
constexpr lanes::Lanes signLanes(int r, int k) {
  return pairMask(r, k, -1.0, 1.0);
}

struct Rotation {
  double c;
  double s;
};

/// The smaller of the two rotations that zero a_pq: tan(2 phi) = 2 a_pq / d, d = a_qq - a_pp,
/// t = tan(phi) = 2 a_pq sign(d) / (|d| + sqrt(d^2 + 4 a_pq^2)) (Rutishauser's t without theta).
/// Warm-started sweeps see small angles: there the series in r = a_pq / d,
/// t = r - r^3 + 2 r^5 (next term 5 r^7) and c = 1 - t^2 / 2 + 3 t^4 / 8 (next 5 t^6 / 16), are
/// exact to rounding for |r| < 1e-3 and replace two square roots and a division by products.
[[gnu::always_inline]] inline Rotation rotationFor(double app, double aqq, double apq) noexcept {
  const double d = aqq - app;
  if (std::abs(apq) < 1e-3 * std::abs(d)) {
    const double r = apq / d;
    const double r2 = r * r;
    const double t = r * (1.0 - r2 * (1.0 - 2.0 * r2));
    const double t2 = t * t;
    const double c = 1.0 - t2 * (0.5 - 0.375 * t2);
    return {c, t * c};
  }
  const double h = std::sqrt(d * d + 4.0 * apq * apq);
  const double t = 2.0 * apq / (d >= 0.0 ? d + h : d - h);
  const double c = 1.0 / std::sqrt(t * t + 1.0);
  return {c, t * c};
}

struct Pair {
  lanes::Matrix& a;  // the matrix being diagonalised, symmetric: column j is also row j
  lanes::Matrix& v;  // the basis
};

/// One round: A <- G^T A G and V <- V G, G the product of the round's three disjoint rotations
/// (identity for pairs that meet the criterion). False, and nothing changed, when all three do.
template <int R>
bool round(Pair m, double tolerance_squared, double floor_squared) noexcept {
  Rotation g[3] = {{1.0, 0.0}, {1.0, 0.0}, {1.0, 0.0}};
  bool rotated = false;
  for (int k = 0; k < 3; ++k) {
    const int p = kRounds[R][k][0];
    const int q = kRounds[R][k][1];
    const double app = m.a.col[p][p];
    const double aqq = m.a.col[q][q];
    const double apq = m.a.col[q][p];
    if (apq * apq > tolerance_squared * std::abs(app * aqq) + floor_squared) {
      g[k] = rotationFor(app, aqq, apq);
      rotated = true;
    }
  }
  if (!rotated) {
    return false;
  }
  // Right: columns p and q mix (A G, V G).
  for (int k = 0; k < 3; ++k) {
    const int p = kRounds[R][k][0];
    const int q = kRounds[R][k][1];
    const lanes::Lanes ap = m.a.col[p];
    const lanes::Lanes aq = m.a.col[q];
    m.a.col[p] = g[k].c * ap - g[k].s * aq;
    m.a.col[q] = g[k].s * ap + g[k].c * aq;
    const lanes::Lanes vp = m.v.col[p];
    const lanes::Lanes vq = m.v.col[q];
    m.v.col[p] = g[k].c * vp - g[k].s * vq;
    m.v.col[q] = g[k].s * vp + g[k].c * vq;
  }
  // Left: G^T mixes entries p and q inside every column; the lane factors are built from
  // constant masks, not by writing single lanes.
  const lanes::Lanes c_lanes =
      pairLanes(R, 0) * g[0].c + pairLanes(R, 1) * g[1].c + pairLanes(R, 2) * g[2].c;
  const lanes::Lanes s_lanes =
      signLanes(R, 0) * g[0].s + signLanes(R, 1) * g[1].s + signLanes(R, 2) * g[2].s;
  for (lanes::Lanes& column : m.a.col) {
    column = c_lanes * column + s_lanes * lanes::permute(column, kPartners[R]);
  }
  return true;
}

/// One round-robin sweep over the pairs that miss the relative criterion; false when none did.
bool sweep(Pair m, double tolerance_squared, double floor_squared) noexcept {
  // Every round runs, whatever the earlier ones did.
  const bool rotated_0 = round<0>(m, tolerance_squared, floor_squared);
  const bool rotated_1 = round<1>(m, tolerance_squared, floor_squared);
  const bool rotated_2 = round<2>(m, tolerance_squared, floor_squared);
  const bool rotated_3 = round<3>(m, tolerance_squared, floor_squared);
  const bool rotated_4 = round<4>(m, tolerance_squared, floor_squared);
  return rotated_0 || rotated_1 || rotated_2 || rotated_3 || rotated_4;
}

/// Whether every off-diagonal entry meets the relative criterion: a column at a time, so the
/// check that ends the iteration costs six vector comparisons instead of a sweep of scalar ones.
bool converged(const lanes::Matrix& a, double tolerance_squared, double floor_squared) noexcept {
  lanes::Lanes diagonal = {};
  for (int c = 0; c < 6; ++c) {
    diagonal[c] = a.col[c][c];
  }
  lanes::LaneIndex violated = {};
  for (int c = 0; c < 6; ++c) {
    lanes::Lanes off_diagonal = a.col[c];
    off_diagonal[c] = 0.0;
    const lanes::Lanes scale = diagonal * diagonal[c];
    const lanes::Lanes magnitude = scale < 0.0 ? -scale : scale;
    violated |= off_diagonal * off_diagonal > tolerance_squared * magnitude + floor_squared;
  }
  for (int r = 0; r < 6; ++r) {
    if (violated[r] != 0) {
      return false;
    }
  }
  return true;
}

/// One Newton-Schulz step B <- B (3 I - B^T B) / 2: squares the departure from orthonormality
/// (Higham, Functions of Matrices, 8.3) for two products instead of six square roots. A basis
/// that is far off (|B^T B - I| > 1e-6, not a previous result) gets Gram-Schmidt instead.
void keepOrthonormal(lanes::Matrix& basis) noexcept {
  const lanes::Matrix gram = lanes::product(lanes::transpose(basis), basis);
  lanes::Matrix correction;
  lanes::Lanes departure = {};
  for (int c = 0; c < 6; ++c) {
    lanes::Lanes identity = {};
    identity[c] = 1.0;
    const lanes::Lanes difference = gram.col[c] - identity;
    departure += difference * difference;
    correction.col[c] = 1.5 * identity - 0.5 * gram.col[c];
  }
  double departure_squared = 0.0;
  for (int r = 0; r < 6; ++r) {
    departure_squared += departure[r];
  }
  if (departure_squared > 1e-12) {
    Matrix6d full;
    lanes::store(basis, full);
    orthonormalise(full);
    basis = lanes::load(full);
    return;
  }
  basis = lanes::product(basis, correction);
}

}  // namespace

namespace lanes {

int trackEigen(const Matrix& matrix, Matrix& basis, Matrix& rotated, double relative_tolerance,
               bool reorthonormalise, int max_sweeps) noexcept {
  if (reorthonormalise) {
    keepOrthonormal(basis);
  }
  rotated = product(transpose(basis), product(matrix, basis));
  Lanes diagonal = {};
  for (int c = 0; c < 6; ++c) {
    diagonal[c] = rotated.col[c][c];
  }
  double largest_diagonal = 0.0;
  for (int c = 0; c < 6; ++c) {
    largest_diagonal = std::max(largest_diagonal, std::abs(diagonal[c]));
  }
  const double floor = 1e-15 * largest_diagonal;
  const double tolerance_squared = relative_tolerance * relative_tolerance;
  int sweeps = 0;
  while (sweeps < max_sweeps && !converged(rotated, tolerance_squared, floor * floor)) {
    sweep({rotated, basis}, tolerance_squared, floor * floor);
    ++sweeps;
  }
  return sweeps;
}

}  // namespace lanes

int trackSymmetricEigen(const Matrix6d& matrix, Matrix6d& basis, Matrix6d& rotated,
                        double relative_tolerance, int max_sweeps) noexcept {
  lanes::Matrix v = lanes::load(basis);
  lanes::Matrix a;
  const int sweeps =
      lanes::trackEigen(lanes::load(matrix), v, a, relative_tolerance, true, max_sweeps);
  lanes::store(v, basis);
  lanes::store(a, rotated);
  rotated = (0.5 * (rotated + rotated.transpose())).eval();
  return sweeps;
}

int symmetricEigenJacobi(const Matrix6d& matrix, Matrix6d& basis, Vector6d& eigenvalues,
                         int max_sweeps) noexcept {
  orthonormalise(basis);
  const Matrix6d rotated = basis.transpose() * matrix * basis;
  // Plain arrays: the rotation loops below index rows and columns symmetrically, which the
  // compiler only keeps in registers when it can see there is no aliasing.
  double a[6][6];
  double v[6][6];
  double norm_squared = 0.0;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      a[r][c] = 0.5 * (rotated(r, c) + rotated(c, r));
      v[r][c] = basis(r, c);
      norm_squared += a[r][c] * a[r][c];
    }
  }
  const double tolerance = 1e-30 * norm_squared;  // (1e-15 relative)^2
  int sweep = 0;
  for (; sweep < max_sweeps; ++sweep) {
    double off_diagonal = 0.0;
    for (int p = 0; p < 5; ++p) {
      for (int q = p + 1; q < 6; ++q) {
        off_diagonal += a[p][q] * a[p][q];
      }
    }
    if (off_diagonal <= tolerance) {
      break;
    }
    for (int p = 0; p < 5; ++p) {
      for (int q = p + 1; q < 6; ++q) {
        const double apq = a[p][q];
        if (apq == 0.0) {
          continue;
        }
        // Rotation that zeroes a(p, q), the smaller of the two angles for stability. For huge
        // theta, theta^2 would overflow; t -> 1 / (2 theta) there (std::hypot would be exact too,
        // but costs as much as the rest of the rotation).
        const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
        const double magnitude = std::abs(theta);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) /
                         (magnitude < 1e150 ? magnitude + std::sqrt(magnitude * magnitude + 1.0)
                                            : 2.0 * magnitude);
        const double c = 1.0 / std::sqrt(t * t + 1.0);
        const double s = t * c;
        a[p][p] -= t * apq;
        a[q][q] += t * apq;
        a[p][q] = 0.0;
        a[q][p] = 0.0;
        for (int r = 0; r < 6; ++r) {
          if (r != p && r != q) {
            const double arp = a[r][p];
            const double arq = a[r][q];
            a[r][p] = a[p][r] = c * arp - s * arq;
            a[r][q] = a[q][r] = s * arp + c * arq;
          }
          const double vrp = v[r][p];
          const double vrq = v[r][q];
          v[r][p] = c * vrp - s * vrq;
          v[r][q] = s * vrp + c * vrq;
        }
      }
    }
  }
  for (int r = 0; r < 6; ++r) {
    eigenvalues[r] = a[r][r];
    for (int c = 0; c < 6; ++c) {
      basis(r, c) = v[r][c];
    }
  }
  return sweep;
}

}  // namespace comply
