#include "urdf_checks.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <limits>

#include "comply/model/model_error.hpp"

namespace comply::model {

// A rotational inertia is physical when its principal moments are non-negative and each is at
// most the sum of the other two (the triangle inequality of a real mass distribution), both up to
// rounding in the URDF's printed digits.
void requirePhysicalInertia(const Eigen::Matrix3d& inertia, const std::string& link_name) {
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia, Eigen::EigenvaluesOnly)
          .eigenvalues();  // ascending
  const double tolerance = 1e-6 * std::max(moments.cwiseAbs().maxCoeff(), 1e-12);
  if (moments[0] < -tolerance || moments[2] > moments[0] + moments[1] + tolerance) {
    throw ModelError(ModelErrc::kInvalidInertia,
                     "link '" + link_name + "' has a non-physical inertia (principal moments " +
                         std::to_string(moments[0]) + ", " + std::to_string(moments[1]) + ", " +
                         std::to_string(moments[2]) +
                         " kg m^2: each must be >= 0 and at most the sum of the other two)");
  }
}

// urdfdom accepts a joint that closes a loop (a link that is its own ancestor) when the root is
// elsewhere; every walk up or down the tree would then run forever. A link is in a loop when
// walking up from it takes more steps than there are links.
void requireTree(const urdf::ModelInterface& urdf) {
  const std::size_t links = urdf.links_.size();
  for (const auto& [name, link] : urdf.links_) {
    std::size_t steps = 0;
    for (auto up = link->getParent(); up; up = up->getParent()) {
      if (++steps > links) {
        throw ModelError(
            ModelErrc::kInvalidUrdf,
            "the joints form a kinematic loop through link '" + name + "'; a URDF must be a tree");
      }
    }
  }
}

void readLimits(const urdf::Joint& joint, JointLimits& limits) {
  if (joint.type == urdf::Joint::CONTINUOUS) {
    limits.lower = -std::numeric_limits<double>::infinity();
    limits.upper = std::numeric_limits<double>::infinity();
  }
  if (joint.limits) {
    if (joint.type != urdf::Joint::CONTINUOUS) {
      limits.lower = joint.limits->lower;
      limits.upper = joint.limits->upper;
      if (!(limits.lower <= limits.upper)) {
        throw ModelError(ModelErrc::kInvalidUrdf, "joint '" + joint.name + "' has a lower limit (" +
                                                      std::to_string(limits.lower) +
                                                      ") above its upper limit (" +
                                                      std::to_string(limits.upper) + ")");
      }
    }
    limits.velocity = joint.limits->velocity;
    limits.effort = joint.limits->effort;
  }
}

}  // namespace comply::model
