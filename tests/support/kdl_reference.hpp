#pragma once
// Test oracle: kinematics and dynamics of a URDF chain computed by Orocos KDL. The URDF is read
// with urdfdom and converted to a KDL::Tree here (not by kdl_parser, and not by our own model
// code), so that a mistake in our URDF handling cannot hide in the reference as well.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "reference_result.hpp"

namespace comply::testing {

class KdlReference {
 public:
  /// Loads `urdf_path` and extracts the chain `base_link` -> `tip_link`. `joint_names` fixes the
  /// order of every joint vector and must list each movable joint of the chain exactly once.
  /// Throws std::runtime_error on any failure (unreadable URDF, unsupported joint type, missing
  /// link, joint_names not matching the chain).
  KdlReference(const std::string& urdf_path, const std::string& base_link,
               const std::string& tip_link, const std::vector<std::string>& joint_names);
  ~KdlReference();
  KdlReference(KdlReference&&) noexcept;
  KdlReference& operator=(KdlReference&&) noexcept;
  KdlReference(const KdlReference&) = delete;
  KdlReference& operator=(const KdlReference&) = delete;

  /// All quantities at (q, dq), both in `joint_names` order. Throws on a size mismatch or when a
  /// KDL solver reports an error.
  ReferenceResult compute(const Eigen::VectorXd& q, const Eigen::VectorXd& dq) const;

  int dof() const;

 private:
  // Behind a pointer: the KDL solvers keep references to the chain, so it must never move, and
  // the KDL headers stay out of the tests that only want the results.
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace comply::testing
