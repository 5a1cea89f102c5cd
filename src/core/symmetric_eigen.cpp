#include "comply/core/symmetric_eigen.hpp"

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

}  // namespace

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
