#include "comply/core/symmetric_eigen.hpp"

#include <algorithm>
#include <cmath>

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

struct Rotation {
  double t;  // tan of the angle
  double c;
  double s;
};

/// The smaller of the two rotations that zero a_pq: tan(2 phi) = 2 a_pq / (a_qq - a_pp), written
/// as t = 2 a_pq sign(d) / (|d| + sqrt(d^2 + 4 a_pq^2)) (Rutishauser's t, one square root and
/// one division fewer than through theta = d / (2 a_pq)).
Rotation rotationFor(double app, double aqq, double apq) noexcept {
  const double d = aqq - app;
  const double h = std::sqrt(d * d + 4.0 * apq * apq);
  const double t = 2.0 * apq / (d >= 0.0 ? d + h : d - h);
  const double c = 1.0 / std::sqrt(t * t + 1.0);
  return {t, c, t * c};
}

/// Column-major 6x6 storage; column j of a symmetric matrix is also its row j.
struct Columns {
  double a[6][6];  // a[column][row]
  double v[6][6];
};

/// A <- G^T A G and V <- V G for the rotation G in the (p, q) plane: mixes columns p and q
/// (contiguous), copies them into rows p and q, and sets the 2x2 pivot block exactly.
void rotate(Columns& m, int p, int q, const Rotation& g) noexcept {
  const double app = m.a[p][p];
  const double aqq = m.a[q][q];
  const double apq = m.a[q][p];
  for (int r = 0; r < 6; ++r) {
    const double x = m.a[p][r];
    const double y = m.a[q][r];
    m.a[p][r] = g.c * x - g.s * y;
    m.a[q][r] = g.s * x + g.c * y;
    const double vx = m.v[p][r];
    const double vy = m.v[q][r];
    m.v[p][r] = g.c * vx - g.s * vy;
    m.v[q][r] = g.s * vx + g.c * vy;
  }
  for (int r = 0; r < 6; ++r) {
    m.a[r][p] = m.a[p][r];
    m.a[r][q] = m.a[q][r];
  }
  m.a[p][p] = app - g.t * apq;
  m.a[q][q] = aqq + g.t * apq;
  m.a[p][q] = 0.0;
  m.a[q][p] = 0.0;
}

/// One round-robin sweep over the pairs that miss the relative criterion; false when none did.
bool sweep(Columns& m, double tolerance_squared, double floor_squared) noexcept {
  bool rotated = false;
  for (const auto& round : kRounds) {
    bool needed[3];
    Rotation rotation[3];
    for (int k = 0; k < 3; ++k) {
      const int p = round[k][0];
      const int q = round[k][1];
      const double apq = m.a[q][p];
      needed[k] = apq * apq > tolerance_squared * std::abs(m.a[p][p] * m.a[q][q]) + floor_squared;
      if (needed[k]) {
        rotation[k] = rotationFor(m.a[p][p], m.a[q][q], apq);
      }
    }
    for (int k = 0; k < 3; ++k) {
      if (needed[k]) {
        rotate(m, round[k][0], round[k][1], rotation[k]);
        rotated = true;
      }
    }
  }
  return rotated;
}

/// One Newton-Schulz step B <- B (3 I - B^T B) / 2: squares the departure from orthonormality
/// (Higham, Functions of Matrices, 8.3) for a few products instead of six square roots. A basis
/// that is far off (not a previous result) gets the full Gram-Schmidt instead.
void keepOrthonormal(Matrix6d& basis) noexcept {
  const Matrix6d gram = basis.transpose() * basis;
  if ((gram - Matrix6d::Identity()).cwiseAbs().maxCoeff() > 1e-6) {
    orthonormalise(basis);
    return;
  }
  basis = basis * (1.5 * Matrix6d::Identity() - 0.5 * gram);
}

}  // namespace

int trackSymmetricEigen(const Matrix6d& matrix, Matrix6d& basis, Matrix6d& rotated,
                        double relative_tolerance, int max_sweeps) noexcept {
  keepOrthonormal(basis);
  const Matrix6d start = basis.transpose() * matrix * basis;
  Columns m;
  double largest_diagonal = 0.0;
  for (int c = 0; c < 6; ++c) {
    for (int r = 0; r < 6; ++r) {
      m.a[c][r] = 0.5 * (start(r, c) + start(c, r));
      m.v[c][r] = basis(r, c);
    }
    largest_diagonal = std::max(largest_diagonal, std::abs(start(c, c)));
  }
  const double floor = 1e-15 * largest_diagonal;
  int sweeps = 0;
  while (sweeps < max_sweeps &&
         sweep(m, relative_tolerance * relative_tolerance, floor * floor)) {
    ++sweeps;
  }
  for (int c = 0; c < 6; ++c) {
    for (int r = 0; r < 6; ++r) {
      rotated(r, c) = m.a[c][r];
      basis(r, c) = m.v[c][r];
    }
  }
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
