#include "kdl_chain.hpp"

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <kdl/frames.hpp>
#include <kdl/tree.hpp>
#include <stdexcept>
#include <string>

namespace comply::testing {
namespace {

[[noreturn]] void fail(const std::string& message) {
  throw std::runtime_error("kdlChainFromUrdf: " + message);
}

KDL::Frame toKdl(const urdf::Pose& pose) {
  return KDL::Frame(
      KDL::Rotation::Quaternion(pose.rotation.x, pose.rotation.y, pose.rotation.z, pose.rotation.w),
      KDL::Vector(pose.position.x, pose.position.y, pose.position.z));
}

/// The URDF joint as a KDL joint placed at the joint origin. KDL wants the axis in the frame the
/// segment starts in (the parent link frame), URDF gives it in the joint frame: rotate it.
KDL::Joint toKdl(const urdf::Joint& joint) {
  const KDL::Frame origin = toKdl(joint.parent_to_joint_origin_transform);
  switch (joint.type) {
    case urdf::Joint::FIXED:
      return KDL::Joint(joint.name, KDL::Joint::Fixed);
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::CONTINUOUS:
    case urdf::Joint::PRISMATIC: {
      KDL::Vector axis(joint.axis.x, joint.axis.y, joint.axis.z);
      if (axis.Norm() < 1e-12) {
        fail("joint '" + joint.name + "' has a zero axis");
      }
      axis.Normalize();
      const KDL::Joint::JointType type =
          joint.type == urdf::Joint::PRISMATIC ? KDL::Joint::TransAxis : KDL::Joint::RotAxis;
      return KDL::Joint(joint.name, origin.p, origin.M * axis, type);
    }
    default:
      fail("joint '" + joint.name + "' has a type KDL chains cannot represent (floating/planar)");
  }
}

/// The link's inertia about the link frame origin, in link axes. URDF gives the rotational
/// inertia about the COM in the inertial frame; KDL's constructor wants it about the COM in link
/// axes (it shifts it to the link origin itself), so only the rotation is applied here.
KDL::RigidBodyInertia toKdl(const urdf::Inertial* inertial) {
  if (inertial == nullptr) {
    return KDL::RigidBodyInertia::Zero();
  }
  Eigen::Matrix3d inertia_in_inertial_frame;
  inertia_in_inertial_frame << inertial->ixx, inertial->ixy, inertial->ixz,  //
      inertial->ixy, inertial->iyy, inertial->iyz,                           //
      inertial->ixz, inertial->iyz, inertial->izz;
  const urdf::Rotation& q = inertial->origin.rotation;
  const Eigen::Matrix3d rotation = Eigen::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix();
  const Eigen::Matrix3d about_com = rotation * inertia_in_inertial_frame * rotation.transpose();
  const urdf::Vector3& com = inertial->origin.position;
  return KDL::RigidBodyInertia(
      inertial->mass, KDL::Vector(com.x, com.y, com.z),
      KDL::RotationalInertia(about_com(0, 0), about_com(1, 1), about_com(2, 2), about_com(0, 1),
                             about_com(0, 2), about_com(1, 2)));
}

/// Adds one segment per child link below `link`, depth first, so every parent exists before its
/// children are hooked onto it. A segment's tip frame is the child link frame at q = 0 (= the
/// joint origin), which is also the frame its inertia is expressed in.
void addChildren(const urdf::Link& link, KDL::Tree& tree) {
  for (const urdf::LinkSharedPtr& child : link.child_links) {
    const urdf::JointSharedPtr& joint = child->parent_joint;
    if (!joint) {
      fail("link '" + child->name + "' has no parent joint");
    }
    const KDL::Segment segment(child->name, toKdl(*joint),
                               toKdl(joint->parent_to_joint_origin_transform),
                               toKdl(child->inertial.get()));
    if (!tree.addSegment(segment, link.name)) {
      fail("could not add segment '" + child->name + "' to the KDL tree");
    }
    addChildren(*child, tree);
  }
}

}  // namespace

KdlUrdfChain kdlChainFromUrdf(const std::string& urdf_path, const std::string& base_link,
                              const std::string& tip_link) {
  if (!std::filesystem::is_regular_file(urdf_path)) {
    fail("no URDF file at '" + urdf_path + "'");
  }
  urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDFFile(urdf_path);
  if (!urdf) {
    fail("urdfdom could not parse '" + urdf_path + "'");
  }
  const urdf::LinkConstSharedPtr root = urdf->getRoot();
  if (!root) {
    fail("'" + urdf_path + "' has no root link");
  }
  // The root link has no segment of its own: its inertia is ignored (fixed base).
  KDL::Tree tree(root->name);
  addChildren(*root, tree);

  KdlUrdfChain result;
  if (!tree.getChain(base_link, tip_link, result.chain)) {
    fail("no chain from '" + base_link + "' to '" + tip_link + "' in '" + urdf_path + "'");
  }
  for (unsigned s = 0; s < result.chain.getNrOfSegments(); ++s) {
    const KDL::Joint& joint = result.chain.getSegment(s).getJoint();
    if (joint.getType() == KDL::Joint::Fixed) {
      continue;
    }
    if (urdf->getJoint(joint.getName())->mimic) {
      fail("mimic joint '" + joint.getName() + "' on the chain is not supported");
    }
    result.movable_joint_names.push_back(joint.getName());
  }
  return result;
}

}  // namespace comply::testing
