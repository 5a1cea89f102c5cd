#pragma once
// Test oracle: kinematics and dynamics of a URDF computed by MuJoCo, through MuJoCo's own URDF
// importer. Everything is expressed in the MuJoCo world frame, which is the frame of the URDF's
// root link; the root link is welded to the world (fixed base).

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "reference_result.hpp"

namespace comply::testing {

class MujocoReference {
 public:
  /// Loads `urdf_path` with MuJoCo. If the URDF has no <mujoco> element, one is added that keeps
  /// fixed-joint links as bodies (so `tip_link` exists), drops visual geoms and does not infer
  /// inertias from geoms (links without <inertial> stay massless, as in URDF). `joint_names`
  /// fixes the order of every joint vector; each must be a hinge or slide joint of the model.
  /// Joints not listed stay at their reference position (0) with zero velocity.
  /// Throws std::runtime_error on any failure, including MuJoCo's compiler message.
  MujocoReference(const std::string& urdf_path, const std::string& tip_link,
                  const std::vector<std::string>& joint_names);

  /// All quantities at (q, dq), both in `joint_names` order. Dynamics are those of the whole
  /// MuJoCo model, so links hanging off the arm beyond the tip (tools, fingers) are included.
  ReferenceResult compute(const Eigen::VectorXd& q, const Eigen::VectorXd& dq) const;

  const mjModel* model() const { return model_.get(); }
  int dof() const { return static_cast<int>(dof_address_.size()); }

 private:
  struct ModelDeleter {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
  };
  struct DataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };

  std::unique_ptr<mjModel, ModelDeleter> model_;
  // compute() is logically const but MuJoCo writes every result into mjData.
  std::unique_ptr<mjData, DataDeleter> data_;
  int tip_body_ = -1;
  std::vector<int> qpos_address_;  // per entry of joint_names
  std::vector<int> dof_address_;   // per entry of joint_names
  // Work buffers, allocated once: jacobian (3 x nv, row major, linear then angular), dense M.
  mutable std::vector<mjtNum> jacp_, jacr_, mass_, bias_, gravity_;
};

}  // namespace comply::testing
