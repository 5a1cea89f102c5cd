#include "mujoco_reference.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "comply/core/temporary_file.hpp"
#include "comply/core/xml_tags.hpp"

namespace comply::testing {
namespace {

[[noreturn]] void fail(const std::string& message) {
  throw std::runtime_error("MujocoReference: " + message);
}

/// The URDF text with a <mujoco> element added when it has none. Without it MuJoCo would fuse
/// fixed-joint links into their parents (the tip frame would vanish), load visual geoms (meshes
/// that may not resolve) and give links without <inertial> the inertia of their geoms, which the
/// URDF semantics (and KDL, and our model) treat as massless.
std::string withMujocoCompilerOptions(std::string xml, const std::string& path) {
  if (findOpeningTag(xml, "mujoco")) {
    return xml;
  }
  const std::optional<XmlTag> robot = findOpeningTag(xml, "robot");
  if (!robot) {
    fail("'" + path + "' has no <robot> element");
  }
  if (robot->selfClosing(xml)) {
    fail("'" + path + "' has an empty <robot/> element");
  }
  xml.insert(robot->end,
             "<mujoco><compiler fusestatic=\"false\" discardvisual=\"true\" "
             "inertiafromgeom=\"false\"/></mujoco>");
  return xml;
}

}  // namespace

MujocoReference::MujocoReference(const std::string& urdf_path, const std::string& tip_link,
                                 const std::vector<std::string>& joint_names) {
  std::ifstream in(urdf_path);
  if (!in) {
    fail("cannot read '" + urdf_path + "'");
  }
  std::stringstream text;
  text << in.rdbuf();

  {
    const TemporaryFile file(withMujocoCompilerOptions(text.str(), urdf_path), "mujoco", ".urdf");
    std::array<char, 1024> error{};
    model_.reset(
        mj_loadXML(file.path().c_str(), nullptr, error.data(), static_cast<int>(error.size())));
    if (!model_) {
      fail("MuJoCo could not load '" + urdf_path + "': " + error.data());
    }
  }
  // MuJoCo's default already, but the oracles must agree by construction, not by coincidence.
  model_->opt.gravity[0] = 0.0;
  model_->opt.gravity[1] = 0.0;
  model_->opt.gravity[2] = -kReferenceGravity;

  data_.reset(mj_makeData(model_.get()));
  if (!data_) {
    fail("mj_makeData failed for '" + urdf_path + "'");
  }

  tip_body_ = mj_name2id(model_.get(), mjOBJ_BODY, tip_link.c_str());
  if (tip_body_ < 0) {
    fail("no body '" + tip_link + "' in '" + urdf_path +
         "' (links merged by MuJoCo? set fusestatic=\"false\")");
  }
  for (const std::string& name : joint_names) {
    const int joint = mj_name2id(model_.get(), mjOBJ_JOINT, name.c_str());
    if (joint < 0) {
      fail("no joint '" + name + "' in '" + urdf_path + "'");
    }
    const int type = model_->jnt_type[joint];
    if (type != mjJNT_HINGE && type != mjJNT_SLIDE) {
      fail("joint '" + name + "' is not a hinge or slide joint");
    }
    const int dof = model_->jnt_dofadr[joint];
    if (std::find(dof_address_.begin(), dof_address_.end(), dof) != dof_address_.end()) {
      fail("joint '" + name + "' is listed twice in joint_names");
    }
    qpos_address_.push_back(model_->jnt_qposadr[joint]);
    dof_address_.push_back(dof);
  }

  const std::size_t nv = static_cast<std::size_t>(model_->nv);
  jacp_.resize(3 * nv);
  jacr_.resize(3 * nv);
  mass_.resize(nv * nv);
  bias_.resize(nv);
  gravity_.resize(nv);
}

ReferenceResult MujocoReference::compute(const Eigen::VectorXd& q,
                                         const Eigen::VectorXd& dq) const {
  const mjModel* m = model_.get();
  mjData* d = data_.get();
  const int n = dof();
  if (q.size() != n || dq.size() != n) {
    fail("compute() expects " + std::to_string(n) + " positions and velocities, got " +
         std::to_string(q.size()) + " and " + std::to_string(dq.size()));
  }

  // qpos0 is 0 for hinge and slide joints (URDF has no reference angle) and a unit quaternion
  // for any ball/free joint, so unlisted joints sit in a valid configuration.
  mju_copy(d->qpos, m->qpos0, m->nq);
  mju_zero(d->qvel, m->nv);
  for (int i = 0; i < n; ++i) {
    d->qpos[qpos_address_[i]] = q(i);
  }

  // Only the position-dependent stages that the quantities below need: no collision detection,
  // no constraints, no passive forces (joint damping/friction from the URDF must not leak in).
  mj_kinematics(m, d);
  mj_comPos(m, d);
  mj_crb(m, d);

  // mj_rne without acceleration is the bias force c(q, dq) = C(q, dq) dq + g(q), i.e. the torque
  // that keeps the arm from accelerating. Its velocity terms come from cvel and cdof_dot, which
  // mj_comVel computes from qvel, so it must be rerun whenever qvel changes.
  mj_comVel(m, d);
  mj_rne(m, d, 0, gravity_.data());
  for (int i = 0; i < n; ++i) {
    d->qvel[dof_address_[i]] = dq(i);
  }
  mj_comVel(m, d);
  mj_rne(m, d, 0, bias_.data());

  mj_jacBody(m, d, jacp_.data(), jacr_.data(), tip_body_);
  mj_fullM(m, mass_.data(), d->qM);

  ReferenceResult result;
  result.position = Eigen::Vector3d(d->xpos[3 * tip_body_], d->xpos[3 * tip_body_ + 1],
                                    d->xpos[3 * tip_body_ + 2]);
  const mjtNum* quat = d->xquat + 4 * tip_body_;  // MuJoCo order: w, x, y, z
  result.orientation = Eigen::Quaterniond(quat[0], quat[1], quat[2], quat[3]).normalized();
  result.jacobian.resize(6, n);
  result.gravity.resize(n);
  result.coriolis.resize(n);
  result.mass_matrix.resize(n, n);
  const int nv = m->nv;
  for (int i = 0; i < n; ++i) {
    const int di = dof_address_[i];
    for (int r = 0; r < 3; ++r) {
      result.jacobian(r, i) = jacp_[r * nv + di];
      result.jacobian(3 + r, i) = jacr_[r * nv + di];
    }
    result.gravity(i) = gravity_[di];
    result.coriolis(i) = bias_[di] - gravity_[di];
    for (int j = 0; j < n; ++j) {
      result.mass_matrix(i, j) = mass_[di * nv + dof_address_[j]];
    }
    // qM includes the motor armature on its diagonal; the rigid-body M does not. URDFs carry no
    // armature, so this is 0 unless a <mujoco> element adds one.
    result.mass_matrix(i, i) -= m->dof_armature[di];
  }
  return result;
}

}  // namespace comply::testing
