#pragma once
// A URDF as parsed, and the checks that it describes a physical robot before the model is built
// from it: a tree (no kinematic loop), links whose mass and inertia a real body can have, joint
// limits in order. Each failure is a ModelError naming the link or joint.

#include <urdf_model/model.h>

#include <Eigen/Core>
#include <memory>
#include <string>

#include "comply/model/model.hpp"

namespace comply::model {

// urdfdom holds a link's children by shared_ptr: a URDF whose joints close a loop (refused by
// requireTree) leaves a cycle that would never be freed. Dropping the child lists on the way out
// frees any tree, loop or not.
class ParsedUrdf {
 public:
  explicit ParsedUrdf(std::shared_ptr<urdf::ModelInterface> model) : model_(std::move(model)) {}
  ~ParsedUrdf() {
    if (model_) {
      for (auto& [name, link] : model_->links_) {
        link->child_links.clear();
      }
    }
  }
  ParsedUrdf(const ParsedUrdf&) = delete;
  ParsedUrdf& operator=(const ParsedUrdf&) = delete;
  explicit operator bool() const { return static_cast<bool>(model_); }
  const urdf::ModelInterface& operator*() const { return *model_; }

 private:
  std::shared_ptr<urdf::ModelInterface> model_;
};

/// Heaviest link a URDF may give [kg]: an arm's links weigh kilograms; 1e12 is a typo.
inline constexpr double kMaxLinkMassKg = 1000.0;

/// Principal moments non-negative and each at most the sum of the other two (within rounding).
void requirePhysicalInertia(const Eigen::Matrix3d& inertia, const std::string& link_name);

/// Every link reaches the root by walking up (no joint closes a loop).
void requireTree(const urdf::ModelInterface& urdf);

/// A joint's limits from its <limit> (a continuous joint has no position bounds even when its
/// <limit> carries some); refuses a lower limit above the upper one.
void readLimits(const urdf::Joint& joint, JointLimits& limits);

}  // namespace comply::model
