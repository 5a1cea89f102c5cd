// URDF -> serial chain. Everything that can be decided once (fixed transforms, folded inertias,
// Rodrigues terms, index maps) is decided here, so the update only multiplies small matrices.

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "chain_path.hpp"
#include "comply/core/rotation.hpp"
#include "comply/core/text_file.hpp"
#include "comply/model/model.hpp"
#include "comply/model/model_error.hpp"
#include "urdf_checks.hpp"
#include "written_inertials.hpp"

namespace comply::model {
namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  transform.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return transform;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string joined;
  for (const auto& name : names) {
    joined += (joined.empty() ? "" : ", ") + name;
  }
  return joined;
}

bool isMovable(int type) {
  return type == urdf::Joint::REVOLUTE || type == urdf::Joint::CONTINUOUS ||
         type == urdf::Joint::PRISMATIC;
}

std::string_view jointTypeName(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE:
      return "revolute";
    case urdf::Joint::CONTINUOUS:
      return "continuous";
    case urdf::Joint::PRISMATIC:
      return "prismatic";
    case urdf::Joint::FLOATING:
      return "floating";
    case urdf::Joint::PLANAR:
      return "planar";
    case urdf::Joint::FIXED:
      return "fixed";
    default:
      return "unknown";
  }
}

/// Mass properties of a set of rigidly connected links, accumulated in one frame.
struct MassAccumulator {
  double mass = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();    // sum m c
  Eigen::Matrix3d inertia_origin = Eigen::Matrix3d::Zero();  // about the frame origin

  void add(const urdf::Inertial& inertial, const Eigen::Isometry3d& link_in_frame,
           const std::string& link_name) {
    const std::array<double, 7> values{inertial.mass, inertial.ixx, inertial.ixy, inertial.ixz,
                                       inertial.iyy,  inertial.iyz, inertial.izz};
    if (!std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); }) ||
        inertial.mass < 0.0) {
      throw ModelError(ModelErrc::kInvalidInertia,
                       "link '" + link_name + "' has a negative or non-finite mass or inertia");
    }
    if (inertial.mass > kMaxLinkMassKg) {
      throw ModelError(ModelErrc::kInvalidInertia,
                       "link '" + link_name + "' has a mass of " + std::to_string(inertial.mass) +
                           " kg, more than any arm's link (" +
                           std::to_string(static_cast<int>(kMaxLinkMassKg)) + " kg)");
    }
    const Eigen::Isometry3d inertial_in_frame = link_in_frame * toIsometry(inertial.origin);
    Eigen::Matrix3d inertia_local;
    inertia_local << inertial.ixx, inertial.ixy, inertial.ixz, inertial.ixy, inertial.iyy,
        inertial.iyz, inertial.ixz, inertial.iyz, inertial.izz;
    requirePhysicalInertia(inertia_local, link_name);
    const Eigen::Matrix3d& rotation = inertial_in_frame.linear();
    const Eigen::Vector3d com = inertial_in_frame.translation();
    // Parallel-axis theorem: inertia about the frame origin.
    inertia_origin +=
        rotation * inertia_local * rotation.transpose() +
        inertial.mass * (com.squaredNorm() * Eigen::Matrix3d::Identity() - com * com.transpose());
    mass += inertial.mass;
    first_moment += inertial.mass * com;
  }
};

// The caller's joint order is kept, so each requested name must name exactly one URDF joint.
std::map<std::string, int> indexRequestedJoints(const urdf::ModelInterface& urdf,
                                                const std::vector<std::string>& joint_names) {
  std::map<std::string, int> user_index;
  std::vector<std::string> unknown;
  std::vector<std::string> duplicate;
  for (int i = 0; i < static_cast<int>(joint_names.size()); ++i) {
    const std::string& name = joint_names[i];
    if (!urdf.getJoint(name)) {
      unknown.push_back(name);
    } else if (!user_index.emplace(name, i).second) {
      duplicate.push_back(name);
    }
  }
  if (!unknown.empty()) {
    throw ModelError(ModelErrc::kUnknownJoint,
                     "robot '" + urdf.getName() + "' has no joint named: " + joinNames(unknown));
  }
  if (!duplicate.empty()) {
    throw ModelError(ModelErrc::kDuplicateJoint,
                     "joints requested more than once: " + joinNames(duplicate));
  }
  return user_index;
}

// Every movable joint on the path is controlled and nothing else is, so no joint is silently
// locked or ignored; returns the number of controlled joints.
std::size_t checkChainMatchesRequest(const std::vector<urdf::JointConstSharedPtr>& path,
                                     const std::map<std::string, int>& user_index,
                                     const ModelOptions& options, const std::string& base_name) {
  std::vector<std::string> missing;
  std::vector<std::string> on_path;
  for (const auto& joint : path) {
    if (joint->type == urdf::Joint::FLOATING || joint->type == urdf::Joint::PLANAR ||
        joint->type == urdf::Joint::UNKNOWN) {
      throw ModelError(ModelErrc::kUnsupportedJoint,
                       "joint '" + joint->name + "' between '" + base_name + "' and '" +
                           options.tip_frame + "' is " + std::string(jointTypeName(joint->type)) +
                           "; only revolute, continuous, prismatic and fixed joints are supported");
    }
    if (isMovable(joint->type)) {
      on_path.push_back(joint->name);
      if (user_index.count(joint->name) == 0) {
        missing.push_back(joint->name);
      }
    }
  }
  std::vector<std::string> off_chain;
  for (const auto& name : options.joint_names) {
    if (std::find(on_path.begin(), on_path.end(), name) == on_path.end()) {
      off_chain.push_back(name);
    }
  }
  if (!off_chain.empty()) {
    throw ModelError(ModelErrc::kJointNotInChain, "joints not movable between '" + base_name +
                                                      "' and '" + options.tip_frame +
                                                      "': " + joinNames(off_chain));
  }
  if (!missing.empty()) {
    throw ModelError(ModelErrc::kMissingJoint,
                     "movable joints between '" + base_name + "' and '" + options.tip_frame +
                         "' not listed as controlled: " + joinNames(missing));
  }
  if (on_path.size() > static_cast<std::size_t>(kMaxDof)) {
    throw ModelError(ModelErrc::kTooManyJoints, "the chain has " + std::to_string(on_path.size()) +
                                                    " movable joints; at most " +
                                                    std::to_string(kMaxDof) + " are supported");
  }
  return on_path.size();
}

// Precomputes the Rodrigues terms so the update evaluates a joint with one sin and one cos.
void placeBody(const urdf::Joint& joint, const Eigen::Isometry3d& joint_in_parent,
               ChainBody& body) {
  body.type = joint.type == urdf::Joint::PRISMATIC ? JointType::kPrismatic : JointType::kRevolute;
  Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
  if (!axis.allFinite() || axis.norm() < 1e-9) {
    throw ModelError(ModelErrc::kInvalidUrdf, "joint '" + joint.name + "' has a zero axis");
  }
  axis.normalize();
  body.axis = axis;
  const Eigen::Matrix3d axis_skew = skew(axis);
  body.rotation_const = joint_in_parent.linear();
  if (body.type == JointType::kRevolute) {
    body.rotation_sin = joint_in_parent.linear() * axis_skew;
    body.rotation_cos = joint_in_parent.linear() * axis_skew * axis_skew;
  }
  body.translation = joint_in_parent.translation();
  body.axis_in_parent = joint_in_parent.linear() * axis;
}

}  // namespace

class ModelBuilder {
 public:
  static Model build(const urdf::ModelInterface& urdf, const WrittenInertials& written,
                     const ModelOptions& options);

 private:
  static std::vector<std::size_t> placeBodies(const std::vector<urdf::JointConstSharedPtr>& path,
                                              const std::map<std::string, int>& user_index,
                                              const Eigen::Isometry3d& tcp_offset, Model& model);
  static void foldInertias(const urdf::ModelInterface& urdf, const WrittenInertials& written,
                           const std::vector<urdf::JointConstSharedPtr>& path,
                           const std::vector<std::size_t>& body_path_position, Model& model);
  static void addArmature(const ModelOptions& options, Model& model);
  static void foldSubtree(const urdf::ModelInterface& urdf, const WrittenInertials& written,
                          const urdf::Link& link, const Eigen::Isometry3d& link_in_body,
                          const std::string* stop_joint, MassAccumulator& accumulator);
};

// Fixed joints vanish here: they accumulate into the placement of the next movable joint, so the
// update walks controlled joints only. Returns each body's position in the path.
std::vector<std::size_t> ModelBuilder::placeBodies(
    const std::vector<urdf::JointConstSharedPtr>& path,
    const std::map<std::string, int>& user_index, const Eigen::Isometry3d& tcp_offset,
    Model& model) {
  Eigen::Isometry3d pending = Eigen::Isometry3d::Identity();  // next joint frame in current body
  int body_index = -1;
  std::vector<std::size_t> body_path_position;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const auto& joint = path[k];
    pending = pending * toIsometry(joint->parent_to_joint_origin_transform);
    if (!isMovable(joint->type)) {
      continue;
    }
    ++body_index;
    body_path_position.push_back(k);
    ChainBody& body = model.bodies_[body_index];
    placeBody(*joint, pending, body);
    body.user_index = user_index.at(joint->name);
    readLimits(*joint, model.limits_[body.user_index]);
    pending = Eigen::Isometry3d::Identity();
  }
  model.tip_in_last_body_ = pending * tcp_offset;
  model.order_is_chain_order_ = true;
  for (int i = 0; i < model.dof_; ++i) {
    model.order_is_chain_order_ = model.order_is_chain_order_ && model.bodies_[i].user_index == i;
  }
  return body_path_position;
}

// The dynamics see one rigid body per controlled joint: everything below its joint up to the next
// controlled joint is folded into one inertia in the body frame. Each body must have a mass: a
// massless one between two controlled joints is what urdfdom leaves of an <inertial> it could not
// read, and MuJoCo refuses to simulate a massless moving body, so `comply validate` would pass a
// robot `comply sim` refuses. The body is checked, not the link: a massless link carrying a
// massive one through a fixed joint is one massive body (and MuJoCo accepts it too).
// A moving body needs a rotational inertia as well as a mass, as MuJoCo does (each principal
// moment above its mjMINVAL, 1e-15 kg m^2): a point mass on a joint's axis makes M(q) singular,
// and `comply validate` would pass a robot `comply sim` refuses.
namespace {

void requireRotationalInertia(const Eigen::Matrix3d& inertia_com, const urdf::Joint& joint) {
  constexpr double kMinimumMoment = 1e-15;  // [kg m^2]
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia_com, Eigen::EigenvaluesOnly)
          .eigenvalues();
  if (!(moments.minCoeff() > kMinimumMoment)) {
    throw ModelError(ModelErrc::kInvalidInertia,
                     "joint '" + joint.name + "' moves a body without rotational inertia: link '" +
                         joint.child_link_name +
                         "' and the links it carries up to the next controlled joint have "
                         "principal moments " +
                         std::to_string(moments[0]) + ", " + std::to_string(moments[1]) + ", " +
                         std::to_string(moments[2]) +
                         " kg m^2 about their centre of mass (each must be above 1e-15)");
  }
}

}  // namespace

void ModelBuilder::foldInertias(const urdf::ModelInterface& urdf, const WrittenInertials& written,
                                const std::vector<urdf::JointConstSharedPtr>& path,
                                const std::vector<std::size_t>& body_path_position, Model& model) {
  for (int i = 0; i < model.dof_; ++i) {
    const auto& joint = path[body_path_position[i]];
    const std::string* stop_joint =
        i + 1 < model.dof_ ? &path[body_path_position[i + 1]]->name : nullptr;
    MassAccumulator accumulator;
    const auto child = urdf.getLink(joint->child_link_name);
    foldSubtree(urdf, written, *child, Eigen::Isometry3d::Identity(), stop_joint, accumulator);
    if (!(accumulator.mass > 0.0)) {
      throw ModelError(ModelErrc::kInvalidInertia,
                       "joint '" + joint->name + "' moves no mass: link '" +
                           joint->child_link_name +
                           "' and the links it carries up to the next controlled joint have no "
                           "<inertial> with a mass");
    }
    ChainBody& body = model.bodies_[i];
    body.mass_kg = accumulator.mass;
    body.com = accumulator.first_moment / accumulator.mass;
    body.inertia_com = accumulator.inertia_origin -
                       accumulator.mass * (body.com.squaredNorm() * Eigen::Matrix3d::Identity() -
                                           body.com * body.com.transpose());
    requireRotationalInertia(body.inertia_com, *joint);
  }
}

// Every link folded here moves with a controlled joint, so its <inertial> is held to the text
// before urdfdom's reading of it is trusted.
void ModelBuilder::foldSubtree(const urdf::ModelInterface& urdf, const WrittenInertials& written,
                               const urdf::Link& link, const Eigen::Isometry3d& link_in_body,
                               const std::string* stop_joint, MassAccumulator& accumulator) {
  written.require(link.name);
  if (link.inertial) {
    accumulator.add(*link.inertial, link_in_body, link.name);
  }
  for (const auto& child_joint : link.child_joints) {
    if (stop_joint != nullptr && child_joint->name == *stop_joint) {
      continue;  // the next controlled joint starts the next body
    }
    // Off-chain branches (a gripper finger, a tool) ride along rigidly, locked at zero.
    const auto child = urdf.getLink(child_joint->child_link_name);
    if (child) {
      foldSubtree(urdf, written, *child,
                  link_in_body * toIsometry(child_joint->parent_to_joint_origin_transform),
                  stop_joint, accumulator);
    }
  }
}

// The rotor inertias, one per controlled joint in the caller's order, each finite and >= 0.
void ModelBuilder::addArmature(const ModelOptions& options, Model& model) {
  if (options.armature.empty()) {
    return;
  }
  if (options.armature.size() != options.joint_names.size()) {
    throw ModelError(ModelErrc::kInvalidOption,
                     "armature has " + std::to_string(options.armature.size()) + " entries for " +
                         std::to_string(options.joint_names.size()) + " joints");
  }
  for (std::size_t i = 0; i < options.armature.size(); ++i) {
    if (!std::isfinite(options.armature[i]) || options.armature[i] < 0.0) {
      throw ModelError(ModelErrc::kInvalidOption,
                       "armature of joint '" + options.joint_names[i] + "' is " +
                           std::to_string(options.armature[i]) + " (must be finite and >= 0)");
    }
  }
  model.armature_ = options.armature;
  for (int i = 0; i < model.dof_; ++i) {
    model.bodies_[i].armature = options.armature[model.bodies_[i].user_index];
  }
}

// The passes run in this order because callers rely on which error a faulty set-up reports first:
// frames, then joint names, then the chain, and only then the geometry.
Model ModelBuilder::build(const urdf::ModelInterface& urdf, const WrittenInertials& written,
                          const ModelOptions& options) {
  requireTree(urdf);
  const ChainEnds ends = findChainEnds(urdf, options);
  const auto path = baseToTipJoints(ends, options.tip_frame);
  const auto user_index = indexRequestedJoints(urdf, options.joint_names);
  const std::size_t dof = checkChainMatchesRequest(path, user_index, options, ends.base_name);

  Model model;
  model.dof_ = static_cast<int>(dof);
  model.joint_names_ = options.joint_names;
  model.limits_.resize(dof);
  model.base_frame_ = ends.base_name;
  model.tip_frame_ = options.tip_frame;
  model.gravity_ = options.gravity_m_per_s2;
  const auto body_path_position = placeBodies(path, user_index, options.tcp_offset, model);
  foldInertias(urdf, written, path, body_path_position, model);
  addArmature(options, model);
  return model;
}

Model Model::fromUrdfString(std::string_view urdf_xml, const ModelOptions& options) {
  const std::string xml(urdf_xml);
  const ParsedUrdf urdf(urdf::parseURDF(xml));
  if (!urdf) {
    throw ModelError(ModelErrc::kInvalidUrdf,
                     "could not parse the URDF (urdfdom printed the details above)");
  }
  return ModelBuilder::build(*urdf, WrittenInertials(xml), options);
}

Model Model::fromUrdfFile(const std::filesystem::path& urdf_path, const ModelOptions& options) {
  const TextFile file = readTextFile(urdf_path);
  if (!file.ok()) {
    throw ModelError(ModelErrc::kFileNotFound, "URDF: " + file.error);
  }
  const ParsedUrdf urdf(urdf::parseURDF(file.text));
  if (!urdf) {
    throw ModelError(ModelErrc::kInvalidUrdf, "could not parse URDF file '" + urdf_path.string() +
                                                  "' (urdfdom printed the details above)");
  }
  try {
    return ModelBuilder::build(*urdf, WrittenInertials(file.text), options);
  } catch (const ModelError& error) {
    throw ModelError(error.code(), error.detail() + " (in '" + urdf_path.string() + "')");
  }
}

}  // namespace comply::model
