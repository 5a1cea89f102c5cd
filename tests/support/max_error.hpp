#pragma once
// The largest differences between two implementations' results (ReferenceResult) over many joint
// states, quantity by quantity, and the check of each against a tolerance.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "reference_result.hpp"

namespace comply::testing {

/// Largest absolute coefficient. A plain loop, not cwiseAbs().maxCoeff(): with -march=native on
/// an AVX-512 machine GCC 12 reports false -Wmaybe-uninitialized / -Warray-bounds warnings inside
/// Eigen's vectorised reductions and small fixed-to-dynamic copies.
template <typename Derived>
double maxAbs(const Eigen::MatrixBase<Derived>& matrix) {
  const typename Derived::PlainObject values = matrix;
  double largest = 0.0;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    largest = std::max(largest, std::abs(values.data()[i]));
  }
  return largest;
}

/// Largest absolute difference per quantity over many comparisons.
struct MaxError {
  double position = 0.0;
  double rotation = 0.0;
  double jacobian = 0.0;
  double gravity = 0.0;
  double coriolis = 0.0;
  double mass_matrix = 0.0;

  void add(const ReferenceResult& a, const ReferenceResult& b) {
    ASSERT_EQ(a.jacobian.cols(), b.jacobian.cols());
    ASSERT_EQ(a.gravity.size(), b.gravity.size());
    ASSERT_EQ(a.mass_matrix.rows(), b.mass_matrix.rows());
    // Rotation matrices, not quaternions: q and -q are the same orientation.
    position = std::max(position, maxAbs(a.position - b.position));
    rotation = std::max(
        rotation, maxAbs(a.orientation.toRotationMatrix() - b.orientation.toRotationMatrix()));
    jacobian = std::max(jacobian, maxAbs(a.jacobian - b.jacobian));
    gravity = std::max(gravity, maxAbs(a.gravity - b.gravity));
    coriolis = std::max(coriolis, maxAbs(a.coriolis - b.coriolis));
    mass_matrix = std::max(mass_matrix, maxAbs(a.mass_matrix - b.mass_matrix));
  }

  void print(const std::string& label) const {
    std::cout << label << " max abs error: position " << position << ", rotation " << rotation
              << ", Jacobian " << jacobian << ", gravity " << gravity << ", Coriolis " << coriolis
              << ", mass matrix " << mass_matrix << "\n";
  }

  /// `inertia_tolerance` applies to M and C dq, the only quantities that depend on rotational
  /// inertias (MuJoCo rounds those: see oracle_agreement_test.cpp).
  void expectWithin(double tolerance, double inertia_tolerance) const {
    EXPECT_LE(position, tolerance);
    EXPECT_LE(rotation, tolerance);
    EXPECT_LE(jacobian, tolerance);
    EXPECT_LE(gravity, tolerance);
    EXPECT_LE(coriolis, inertia_tolerance);
    EXPECT_LE(mass_matrix, inertia_tolerance);
  }
};

}  // namespace comply::testing
