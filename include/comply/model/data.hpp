#pragma once
// Results and scratch of one model update (Featherstone's "data"). Sized once from a Model, then
// reused every cycle: all storage is inline, so updating never touches the heap.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>

#include "comply/core/capacity.hpp"

namespace comply::model {

class Model;

/// Model quantities a caller can request; combine with |.
enum class Quantity : std::uint32_t {
  kNone = 0,
  kPose = 1U << 0,            ///< tip position and orientation
  kJacobian = 1U << 1,        ///< geometric tip Jacobian
  kGravity = 1U << 2,         ///< gravity torque g(q)
  kCoriolis = 1U << 3,        ///< Coriolis and centrifugal torque C(q, dq) dq
  kMassMatrix = 1U << 4,      ///< joint-space inertia M(q)
  kPayloadGravity = 1U << 5,  ///< gravity torque of Data::payload
  kAll = (1U << 6) - 1,
};

constexpr Quantity operator|(Quantity a, Quantity b) {
  return static_cast<Quantity>(static_cast<std::uint32_t>(a) | static_cast<std::uint32_t>(b));
}
constexpr Quantity operator&(Quantity a, Quantity b) {
  return static_cast<Quantity>(static_cast<std::uint32_t>(a) & static_cast<std::uint32_t>(b));
}
constexpr bool contains(Quantity set, Quantity item) { return (set & item) == item; }

/// A load carried by the tool (gripper + object): its gravity is compensated separately from the
/// arm's because it changes at run time.
struct Payload {
  double mass_kg = 0.0;
  Eigen::Vector3d com_in_tip{0.0, 0.0, 0.0};  ///< centre of mass in the tip frame [m]
};

class Data {
 public:
  explicit Data(const Model& model);

  // ---- input --------------------------------------------------------------------------------
  Payload payload;  ///< used when Quantity::kPayloadGravity is requested

  // ---- results, valid for the quantities of the last successful update ----------------------
  Quantity computed = Quantity::kNone;
  Eigen::Vector3d tip_position = Eigen::Vector3d::Zero();  ///< base frame [m]
  Eigen::Quaterniond tip_orientation = Eigen::Quaterniond::Identity();  ///< base frame, w >= 0
  Eigen::Matrix3d tip_rotation = Eigen::Matrix3d::Identity();           ///< same as a matrix
  /// 6 x dof, linear rows first, base-frame axes, reference point = tip origin; caller's order.
  Jacobian jacobian;
  JointVector gravity;          ///< g(q) [N m], the torque that holds the arm still
  JointVector coriolis;         ///< C(q, dq) dq [N m]
  JointMatrix mass_matrix;      ///< M(q) [kg m^2], caller's joint order
  JointVector payload_gravity;  ///< gravity torque of the payload [N m]

  // ---- scratch in chain order (kept public for tests and diagnostics; not an interface) -----
  struct BodyState {
    Eigen::Matrix3d rotation;    ///< body frame in base frame
    Eigen::Vector3d origin;      ///< joint frame origin in base frame [m]
    Eigen::Vector3d axis;        ///< joint axis in base frame (unit)
    Eigen::Vector3d com;         ///< body centre of mass in base frame [m]
    Eigen::Matrix3d inertia_about_base_origin;  ///< base axes [kg m^2]; dynamics passes only
  };
  std::array<BodyState, kMaxDof> bodies{};
};

}  // namespace comply::model
