#include "kdl_reference.hpp"

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <filesystem>
#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl/frames.hpp>
#include <kdl/jacobian.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/jntspaceinertiamatrix.hpp>
#include <kdl/tree.hpp>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "kdl_chain.hpp"

namespace comply::testing {
namespace {

[[noreturn]] void fail(const std::string& message) {
  throw std::runtime_error("KdlReference: " + message);
}

}  // namespace

struct KdlReference::Impl {
  KDL::Chain chain;
  // chain index of the joint at each position of joint_names
  std::vector<int> chain_index;
  KDL::ChainFkSolverPos_recursive fk{chain};
  KDL::ChainJntToJacSolver jacobian{chain};
  KDL::ChainDynParam dynamics{chain, KDL::Vector(0.0, 0.0, -kReferenceGravity)};
  KDL::JntArray q, dq, gravity, coriolis;
  KDL::Jacobian jac;
  KDL::JntSpaceInertiaMatrix mass;

  // The solvers keep a reference to `chain` and size their work arrays from it when built: the
  // member order above makes sure the chain is complete by then, and Impl never moves.
  explicit Impl(KDL::Chain c) : chain(std::move(c)) {
    const unsigned n = chain.getNrOfJoints();
    for (KDL::JntArray* joint_array : {&q, &dq, &gravity, &coriolis}) {
      joint_array->resize(n);
    }
    jac.resize(n);
    mass.resize(n);
  }
};

KdlReference::KdlReference(const std::string& urdf_path, const std::string& base_link,
                           const std::string& tip_link,
                           const std::vector<std::string>& joint_names) {
  KdlUrdfChain urdf_chain = kdlChainFromUrdf(urdf_path, base_link, tip_link);
  std::unordered_map<std::string, int> chain_index;
  for (const std::string& name : urdf_chain.movable_joint_names) {
    chain_index.emplace(name, static_cast<int>(chain_index.size()));
  }
  if (joint_names.size() != chain_index.size()) {
    fail("joint_names has " + std::to_string(joint_names.size()) + " names but the chain from '" +
         base_link + "' to '" + tip_link + "' has " + std::to_string(chain_index.size()) +
         " movable joints");
  }
  std::vector<int> index;
  for (const std::string& name : joint_names) {
    const auto found = chain_index.find(name);
    if (found == chain_index.end()) {
      fail("'" + name + "' is not a movable joint on the chain from '" + base_link + "' to '" +
           tip_link + "'");
    }
    if (std::find(index.begin(), index.end(), found->second) != index.end()) {
      fail("joint '" + name + "' is listed twice in joint_names");
    }
    index.push_back(found->second);
  }

  impl_ = std::make_unique<Impl>(std::move(urdf_chain.chain));
  impl_->chain_index = std::move(index);
}

KdlReference::~KdlReference() = default;
KdlReference::KdlReference(KdlReference&&) noexcept = default;
KdlReference& KdlReference::operator=(KdlReference&&) noexcept = default;

int KdlReference::dof() const {
  return static_cast<int>(impl_->chain_index.size());
}

ReferenceResult KdlReference::compute(const Eigen::VectorXd& q, const Eigen::VectorXd& dq) const {
  Impl& s = *impl_;
  const int n = dof();
  if (q.size() != n || dq.size() != n) {
    fail("compute() expects " + std::to_string(n) + " positions and velocities, got " +
         std::to_string(q.size()) + " and " + std::to_string(dq.size()));
  }
  for (int i = 0; i < n; ++i) {
    s.q(s.chain_index[i]) = q(i);
    s.dq(s.chain_index[i]) = dq(i);
  }

  KDL::Frame tip;
  if (s.fk.JntToCart(s.q, tip) < 0) {
    fail("ChainFkSolverPos_recursive failed");
  }
  if (s.jacobian.JntToJac(s.q, s.jac) < 0) {
    fail("ChainJntToJacSolver failed");
  }
  if (s.dynamics.JntToMass(s.q, s.mass) < 0 || s.dynamics.JntToGravity(s.q, s.gravity) < 0 ||
      s.dynamics.JntToCoriolis(s.q, s.dq, s.coriolis) < 0) {
    fail("ChainDynParam failed");
  }

  ReferenceResult result;
  result.position = Eigen::Vector3d(tip.p.x(), tip.p.y(), tip.p.z());
  double x, y, z, w;
  tip.M.GetQuaternion(x, y, z, w);
  result.orientation = Eigen::Quaterniond(w, x, y, z).normalized();
  result.jacobian.resize(6, n);
  result.gravity.resize(n);
  result.coriolis.resize(n);
  result.mass_matrix.resize(n, n);
  for (int i = 0; i < n; ++i) {
    const int ci = s.chain_index[i];
    // KDL twists are (linear, angular) with the reference point at the tip origin, base axes.
    result.jacobian.col(i) = s.jac.data.col(ci);
    result.gravity(i) = s.gravity(ci);
    result.coriolis(i) = s.coriolis(ci);
    for (int j = 0; j < n; ++j) {
      result.mass_matrix(i, j) = s.mass(ci, s.chain_index[j]);
    }
  }
  return result;
}

}  // namespace comply::testing
