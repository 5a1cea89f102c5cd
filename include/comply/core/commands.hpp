#pragma once
// The command schemas a user sends (docs/design.md, "Command schema"). The members come from the
// field tables of schema/table.hpp, so names are the same in the C buses (plugin/abi.h), JSON files
// and messages. Poses, twists and wrenches are in the base frame; gain blocks in the task frame,
// whose orientation travels with the command.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>

#include "comply/core/capacity.hpp"
#include "comply/schema/table.hpp"

namespace comply {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// A wire stamp [ns since the epoch] as whole seconds and nanoseconds in [0, 1e9), as
/// builtin_interfaces/Time holds it (a stamp before the epoch has negative seconds).
struct StampParts {
  std::int64_t sec = 0;
  std::int64_t nanosec = 0;
};
constexpr StampParts splitStamp(std::int64_t stamp_ns) noexcept {
  const std::int64_t sec = stamp_ns / 1'000'000'000 - (stamp_ns % 1'000'000'000 < 0 ? 1 : 0);
  return {sec, stamp_ns - sec * 1'000'000'000};
}

/// A wire stamp [ns since the epoch] as a command's stamp_s [s]: whole seconds plus the fraction,
/// one formula for every host, so that one stamp is always the same double (the command gate
/// matches the stamp in force against the commands it accepted).
constexpr double stampSeconds(std::int64_t stamp_ns) noexcept {
  const StampParts parts = splitStamp(stamp_ns);
  return static_cast<double>(parts.sec) + 1e-9 * static_cast<double>(parts.nanosec);
}

/// A stamp_s [s] (or any time in seconds) as nanoseconds, to the nearest one.
inline std::int64_t stampNanoseconds(double stamp_s) noexcept {
  return std::llround(stamp_s * 1e9);
}

/// Field groups of a command; a sender sets only those it updates, the rest stays in force.
/// Bit values equal COMPLY_FIELD_* of the plugin ABI.
enum class CommandField : std::uint32_t {
  kNone = 0,
  kPosition = 1U << 0,      ///< joint position | Cartesian position + orientation
  kVelocity = 1U << 1,      ///< joint velocity | Cartesian twist
  kAcceleration = 1U << 2,  ///< joint | Cartesian acceleration
  kStiffness = 1U << 3,     ///< joint stiffness | both Cartesian stiffness blocks
  kDamping = 1U << 4,       ///< joint damping | Cartesian damping blocks, mode and ratios
  kTaskFrame = 1U << 5,     ///< Cartesian task-frame orientation
  kWrenchFeedforward = 1U << 6,
  kTorqueFeedforward = 1U << 7,
  kNullspace = 1U << 8,  ///< nullspace target, stiffness and damping
  kForce = 1U << 9,      ///< Cartesian force axes and wrench target
  kReflex = 1U << 10,    ///< the contact reflex's thresholds
  kWorkspace = 1U << 11, ///< a box the Cartesian TCP stays inside
  kAll = (1U << 12) - 1,
};

constexpr CommandField operator|(CommandField a, CommandField b) {
  return static_cast<CommandField>(static_cast<std::uint32_t>(a) | static_cast<std::uint32_t>(b));
}
constexpr bool has(CommandField set, CommandField field) {
  return (static_cast<std::uint32_t>(set) & static_cast<std::uint32_t>(field)) != 0;
}

/// Joint impedance command; the fields (units, constraints) are the rows of
/// COMPLY_JOINT_COMMAND_FIELDS in schema/table.hpp.
struct JointCommand {
  double stamp_s = 0.0;  ///< sender time [s]; must not go backwards
  CommandField fields = CommandField::kAll;
  COMPLY_JOINT_COMMAND_FIELDS(COMPLY_SCHEMA_MEMBER)

  /// All vectors sized `dof` and zero.
  static JointCommand zero(int dof);
};

enum class DampingMode : std::int32_t {
  kAbsolute = 0,  ///< damping blocks as sent
  kRatio = 1,     ///< damping ratios per task axis, turned into D against the Cartesian inertia
};

/// Cartesian impedance command; the fields (units, constraints) are the rows of
/// COMPLY_CARTESIAN_COMMAND_FIELDS in schema/table.hpp.
struct CartesianCommand {
  double stamp_s = 0.0;  ///< sender time [s]; must not go backwards
  CommandField fields = CommandField::kAll;
  COMPLY_CARTESIAN_COMMAND_FIELDS(COMPLY_SCHEMA_MEMBER)

  /// Zero gains, identity orientations, joint vectors sized `dof` and zero.
  static CartesianCommand zero(int dof);
};

}  // namespace comply
