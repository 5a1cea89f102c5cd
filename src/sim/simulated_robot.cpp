// The simulated arm's setup: its scene loaded, joints found, dynamics and contacts configured,
// drives tuned, and the home pose taken.

#include "comply/sim/simulated_robot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "comply/model/model.hpp"
#include "comply/sim/sim_error.hpp"

namespace comply::sim {
namespace {

// Contact filter bits. Robot geoms (arm and tool) have contype kRobotBit and conaffinity
// kWorldBit: they touch the floor and objects (contype 1, conaffinity 1, MuJoCo's default) but
// never each other. The URDF's collision volumes are coarse and overlap between non-adjacent
// links in ordinary poses; a real arm has no such self-contact.
constexpr int kWorldBit = 1;
constexpr int kRobotBit = 2;

int bodyId(const mjModel& model, const std::string& name, const std::string& robot) {
  const int id = mj_name2id(&model, mjOBJ_BODY, name.c_str());
  if (id < 0) {
    throw SimError("the MuJoCo model of " + robot + " has no body '" + name + "'");
  }
  return id;
}

void checkPerJoint(const std::vector<double>& values, std::size_t dof, const char* key,
                   const std::string& robot) {
  if (values.size() != dof) {
    throw SimError("robot.yaml of " + robot + ": joint_dynamics." + key + " has " +
                   std::to_string(values.size()) + " entries, expected " + std::to_string(dof));
  }
}

void checkPlantOptions(const PlantOptions& options) {
  if (!(options.control_period_s > 0.0) || options.substeps < 1) {
    throw SimError("control period must be > 0 s and substeps >= 1 (got " +
                   std::to_string(options.control_period_s) + " s, " +
                   std::to_string(options.substeps) + ")");
  }
  if (!(options.position_noise_rad >= 0.0) || !(options.velocity_noise_rad_per_s >= 0.0)) {
    throw SimError("measurement noise must be >= 0");
  }
  if (!(options.friction_scale >= 0.0) || !std::isfinite(options.friction_scale)) {
    throw SimError("friction scale must be finite and >= 0 (got " +
                   std::to_string(options.friction_scale) + ")");
  }
}

/// robot.yaml's damping, armature and Coulomb friction (scaled) on the controlled joints' dofs.
void applyJointDynamics(const model::JointDynamics& dynamics, const std::vector<int>& dof_address,
                        double friction_scale, const std::string& robot, mjModel& model) {
  const std::size_t dof = dof_address.size();
  checkPerJoint(dynamics.damping, dof, "damping", robot);
  checkPerJoint(dynamics.armature, dof, "armature", robot);
  checkPerJoint(dynamics.frictionloss, dof, "frictionloss", robot);
  for (std::size_t i = 0; i < dof; ++i) {
    model.dof_damping[dof_address[i]] = dynamics.damping[i];
    model.dof_armature[dof_address[i]] = dynamics.armature[i];
    model.dof_frictionloss[dof_address[i]] = friction_scale * dynamics.frictionloss[i];
  }
}

/// The colliding geoms of the tree rooted at `robot_root` touch the world but not each other.
void keepRobotOutOfSelfContact(int robot_root, mjModel& model) {
  for (int geom = 0; geom < model.ngeom; ++geom) {
    const bool collides = model.geom_contype[geom] != 0 || model.geom_conaffinity[geom] != 0;
    if (collides && robot_root != 0 && model.body_rootid[model.geom_bodyid[geom]] == robot_root) {
      model.geom_contype[geom] = kRobotBit;
      model.geom_conaffinity[geom] = kWorldBit;
    }
  }
}

}  // namespace

SimulatedRobot::SimulatedRobot(const model::RobotDescription& robot, const PlantOptions& options)
    : control_period_s_(options.control_period_s),
      substeps_(options.substeps),
      noise_generator_(options.seed),
      position_noise_rad_(options.position_noise_rad),
      velocity_noise_rad_per_s_(options.velocity_noise_rad_per_s),
      wrench_sensor_offset_(options.wrench_sensor_offset),
      actuation_(options.actuation) {
  checkPlantOptions(options);
  const std::string tip = options.tip_frame.empty() ? robot.tcp_frame : options.tip_frame;
  SceneOptions scene = options.scene;
  model_.reset(loadModelFromXml(buildSceneXml(robot, scene), "the scene of " + robot.name));
  model_->opt.timestep = control_period_s_ / substeps_;

  // Effort limits from the URDF, as the controller's model reads them.
  const model::Model chain = robot.loadModel(tip);
  const std::size_t dof = robot.joints.size();
  for (std::size_t i = 0; i < dof; ++i) {
    const std::string& name = robot.joints[i];
    const int joint = mj_name2id(model_.get(), mjOBJ_JOINT, name.c_str());
    if (joint < 0) {
      throw SimError("the MuJoCo model of " + robot.name + " has no joint '" + name + "'");
    }
    if (model_->jnt_type[joint] != mjJNT_HINGE && model_->jnt_type[joint] != mjJNT_SLIDE) {
      throw SimError("joint '" + name + "' of " + robot.name + " is not revolute or prismatic");
    }
    qpos_address_.push_back(model_->jnt_qposadr[joint]);
    dof_address_.push_back(model_->jnt_dofadr[joint]);
    effort_limit_.push_back(chain.limits(static_cast<int>(i)).effort);
  }
  applied_.assign(dof, 0.0);
  held_position_.assign(dof, 0.0);
  link_side_torque_ = options.link_side_torque;
  link_torque_.assign(dof, 0.0);
  dof_friction_.assign(static_cast<std::size_t>(model_->nv), 0.0);

  if (options.joint_dynamics && robot.joint_dynamics) {
    applyJointDynamics(*robot.joint_dynamics, dof_address_, options.friction_scale, robot.name,
                       *model_);
  }

  base_body_ = bodyId(*model_, robot.base_frame, robot.name);
  tip_body_ = bodyId(*model_, tip, robot.name);
  tool_body_.assign(static_cast<std::size_t>(model_->nbody), false);
  for (int body = 0; body < model_->nbody; ++body) {
    // Bodies are numbered parents first, so one pass marks the whole TCP subtree.
    tool_body_[body] = body == tip_body_ || (body > 0 && tool_body_[model_->body_parentid[body]]);
  }
  keepRobotOutOfSelfContact(model_->body_rootid[base_body_], *model_);

  data_.reset(mj_makeData(model_.get()));
  if (!data_) {
    throw SimError("MuJoCo could not allocate the simulation data of " + robot.name);
  }
  setJointPositions(robot.home);
  configureServos(options);
}

void SimulatedRobot::configureServos(const PlantOptions& options) {
  if (!(options.servo_bandwidth_hz > 0.0) || !std::isfinite(options.servo_bandwidth_hz)) {
    throw SimError("the servo bandwidth must be a positive number of Hz (got " +
                   std::to_string(options.servo_bandwidth_hz) + ")");
  }
  const std::size_t dof = qpos_address_.size();
  drive_command_.resize(static_cast<int>(dof));
  drive_command_.mode = actuation_;
  servo_integral_.assign(dof, 0.0);
  velocity_reference_.assign(dof, 0.0);
  // A triple pole at the bandwidth for each joint's own inertia at home (armature included):
  // (s + w)^3 = s^3 + 3w s^2 + 3w^2 s + w^3, times the inertia.
  const double w = 2.0 * M_PI * options.servo_bandwidth_hz;
  for (std::size_t i = 0; i < dof; ++i) {
    const double inertia = data_->qM[model_->dof_Madr[dof_address_[i]]];
    servo_kd_.push_back(3.0 * w * inertia);
    servo_kp_.push_back(3.0 * w * w * inertia);
    servo_ki_.push_back(w * w * w * inertia);
  }
}

SimulatedRobot::~SimulatedRobot() = default;

void SimulatedRobot::setJointPositions(std::span<const double> position) {
  if (position.size() != qpos_address_.size()) {
    throw std::invalid_argument("setJointPositions: expected " +
                                std::to_string(qpos_address_.size()) + " positions, got " +
                                std::to_string(position.size()));
  }
  for (std::size_t i = 0; i < position.size(); ++i) {
    data_->qpos[qpos_address_[i]] = position[i];
  }
  mju_zero(data_->qvel, model_->nv);
  mju_zero(data_->qacc_warmstart, model_->nv);
  mju_zero(data_->qfrc_applied, model_->nv);
  forward();
  // The arm starts held by its drives, as a real arm in its idle holding mode before a controller
  // takes over: they apply the gravity torque of this pose (the bias force at rest), so a wrapper
  // that seeds its torque-rate limit from the measured effort starts without a jump.
  for (std::size_t i = 0; i < applied_.size(); ++i) {
    applied_[i] =
        std::clamp(data_->qfrc_bias[dof_address_[i]], -effort_limit_[i], effort_limit_[i]);
    data_->qfrc_applied[dof_address_[i]] = applied_[i];
  }
  // Held, not falling: the accelerations (and the wrist sensor's first reading, the tool's weight
  // on the flange) are those of the arm at rest before the first step.
  forward();
  link_torque_sensed_ = false;  // at rest again: the sensors read the drives' hold
}

void SimulatedRobot::forward() noexcept {
  mj_forward(model_.get(), data_.get());
}

}  // namespace comply::sim
