#pragma once
// Operations derived from the command schema tables (schema/table.hpp): bus conversion, merging
// by field group, the reference rules and field validation, for the Cartesian and the joint
// command. Light on purpose (no templates): the wrapper and every app include it; the generic
// machinery behind it is in schema/generic.hpp.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/plugin/abi.h"

namespace comply::schema {

enum class CommandKind : std::uint8_t { kCartesian, kJoint };

enum class FieldKind : std::uint8_t {
  kVector3,      ///< 3 numbers
  kVector6,      ///< 6 numbers, linear first
  kJointVector,  ///< one number per joint (dof)
  kBlock3,       ///< 3x3 gain block, row-major on the bus and in JSON
  kQuaternion,   ///< x y z w on the bus and in JSON
  kEnum,         ///< a name in JSON, an int32 on the bus
};

enum class Constraint : std::uint8_t {
  kNone,
  kNonNegative,
  kSymmetricPsd,
  kUnitQuaternion,
  kSelection,  ///< every entry 0 or 1 (a selection of axes)
  kThreshold,  ///< every entry >= 0, 0 standing for the controller file's value
};

/// What the reference rules do with a field.
enum class Role : std::uint8_t {
  kNone,
  kSeedTcpPosition,     ///< seeded from the measured TCP position
  kSeedTcpOrientation,  ///< seeded from the measured TCP orientation
  kSeedJointPosition,   ///< seeded from the measured joint positions
  kZeroOnStop,          ///< a rate: zero when seeding and when motion stops
};

/// A named value of an enum field (JSON name, bus number).
struct EnumValue {
  std::string_view name;
  int number;
};

/// One table row, for documentation and generated messages.
struct FieldInfo {
  std::string_view name;
  CommandField group;
  FieldKind kind;
  std::string_view cpp_type;
  std::string_view unit;
  Constraint constraint;
  Role role;
  std::string_view description;
  std::vector<EnumValue> values;  ///< kEnum: its values; empty otherwise
};

/// One field group: its mask bit and the name used in JSON `fields` lists.
struct GroupInfo {
  CommandField field;
  std::string_view name;
  std::string_view description;
};

std::span<const FieldInfo> fields(CommandKind kind);
std::span<const GroupInfo> groups();
std::string_view toString(CommandKind kind);
std::string_view toString(FieldKind kind);
std::string_view toString(Constraint constraint);

/// The largest gain entry the schema accepts in `unit` (a gain field's unit in the tables), or
/// infinity for a unit that has none. Two orders of magnitude above the stiffest and most damped
/// settings arm vendors' own impedance controllers accept: a value beyond it is a typo or a unit
/// mistake, never a tuning, and the torque it asks for only saturates the joints.
double gainLimit(std::string_view unit) noexcept;
/// The largest entry the schema accepts in a rate or feedforward field of `unit` (twist,
/// velocity, acceleration, wrench, torque), or infinity for a unit that has none (positions,
/// whose reach is checked against the measured pose instead). Twenty to a hundred times what the
/// fastest and strongest torque-controlled arms reach: a value beyond it is a unit mistake or a
/// corrupted number, and would only pin every joint at its effort limit.
double valueLimit(std::string_view unit) noexcept;
std::string_view toString(Role role);

/// Bit i set: field i of a kind's table (table order). Which keys a JSON object gave, say.
using FieldSet = std::uint64_t;

// --- quaternions as x y z w, the order of the buses, JSON and ROS messages ---

inline void toXyzw(const Eigen::Quaterniond& q, double* xyzw) noexcept {
  xyzw[0] = q.x();
  xyzw[1] = q.y();
  xyzw[2] = q.z();
  xyzw[3] = q.w();
}
inline Eigen::Quaterniond fromXyzw(const double* xyzw) noexcept {
  return {xyzw[3], xyzw[0], xyzw[1], xyzw[2]};  // Eigen's constructor takes w first
}

// --- 3x3 gain blocks as 9 numbers, row-major, the order of the buses and the wire ---

inline void toRowMajor(const Eigen::Matrix3d& block, double* row_major) noexcept {
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>{row_major} = block;
}
inline Eigen::Matrix3d fromRowMajor(const double* row_major) noexcept {
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(row_major);
}

// --- buses (plugin/abi.h) ---

/// The bus for `dof` joints: joint arrays hold `dof` entries and zeros past them.
comply_cartesian_command toBus(const CartesianCommand& command, int dof);
comply_joint_command toBus(const JointCommand& command, int dof);
/// Back to the C++ type: joint vectors sized `bus.dof`.
CartesianCommand fromBus(const comply_cartesian_command& bus);
JointCommand fromBus(const comply_joint_command& bus);

// --- merging: the groups set in `incoming.fields` and the stamp; `into.fields` gains them ---

/// Real-time safe: no allocation, no throw.
void mergeBus(comply_cartesian_command& into, const comply_cartesian_command& incoming) noexcept;
void mergeBus(comply_joint_command& into, const comply_joint_command& incoming) noexcept;
void merge(CartesianCommand& into, const CartesianCommand& incoming);
void merge(JointCommand& into, const JointCommand& incoming);
/// Copies only the fields in `keys` (no stamp, no mask): what a partial JSON object gave.
void assign(CartesianCommand& into, const CartesianCommand& from, FieldSet keys);
void assign(JointCommand& into, const JointCommand& from, FieldSet keys);

// --- reference rules, from the field roles ---

/// Seeded fields from `measured`, rate fields zero. Buses: real-time safe.
void seedReference(comply_cartesian_command& bus, const MeasuredPose& measured) noexcept;
void seedReference(comply_joint_command& bus, const MeasuredPose& measured) noexcept;
void seedReference(CartesianCommand& command, const MeasuredPose& measured);
void seedReference(JointCommand& command, const MeasuredPose& measured);
/// Rate fields zero: holding a reference means holding its pose. Buses: real-time safe.
void stopMotion(comply_cartesian_command& bus) noexcept;
void stopMotion(comply_joint_command& bus) noexcept;
void stopMotion(CartesianCommand& command) noexcept;
void stopMotion(JointCommand& command) noexcept;

// --- validation of the fields a command sets ---

struct CheckOptions {
  double quaternion_tolerance = 1e-3;  ///< |norm - 1| renormalised below, rejected above
  double gain_tolerance = 1e-9;        ///< symmetry / PSD tolerance, relative
};

enum class Violation : std::uint8_t {
  kNone,
  kWrongSize,         ///< a joint vector without `dof` entries
  kNonFinite,         ///< NaN or infinity
  kNotUnit,           ///< a quaternion too far from unit norm
  kNegative,          ///< a non-negative field with a negative entry
  kNotSymmetricPsd,   ///< a gain block that is not symmetric positive semi-definite
  kGainTooLarge,      ///< a gain entry above gainLimit() of its unit
  kValueTooLarge,     ///< a rate or feedforward entry above valueLimit() of its unit
  kNotSelection,      ///< a selection with an entry other than 0 or 1
  kNegativeThreshold  ///< a threshold with a negative entry
};

struct CheckResult {
  Violation violation = Violation::kNone;
  std::string field;    ///< the failing field's name; empty when ok
  std::string message;  ///< names the field; empty when ok
  [[nodiscard]] bool ok() const noexcept { return violation == Violation::kNone; }
};

/// Checks the fields of the groups `command.fields` sets, in three passes over the table (sizes,
/// then finiteness, then constraints), and renormalises their quaternions in place (so on a
/// failure `command` may be half normalised).
CheckResult checkFields(CartesianCommand& command, int dof, const CheckOptions& options = {});
CheckResult checkFields(JointCommand& command, int dof, const CheckOptions& options = {});

}  // namespace comply::schema
