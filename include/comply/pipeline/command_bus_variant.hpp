#pragma once
// The command in force on the real-time side: the plugin bus of the controller's command kind.
// Held as a variant so one cycle serves joint and Cartesian control; the reference rules (merge a
// partial command, seed from the measured pose, stop the motion) are the schema's, per bus type.

#include <cstdint>
#include <utility>
#include <variant>

#include "comply/core/commands.hpp"
#include "comply/core/state.hpp"
#include "comply/plugin/abi.h"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {

using CommandBus = std::variant<comply_joint_command, comply_cartesian_command>;

/// Which command is in force. The wrapper numbers every command and chunk it accepts, in order;
/// the number travels with it through the intake queue and the cycle to the command gate, which
/// settles outcomes by it, and to the state and the recording. The stamp is the sender's, exact
/// (integer nanoseconds: a double in seconds resolves only about 0.24 us at today's epoch).
struct CommandId {
  std::uint64_t sequence = 0;  ///< 0: none accepted yet (the controller file's initial command)
  std::int64_t stamp_ns = 0;   ///< the sender's stamp [ns since its epoch]

  friend bool operator==(const CommandId&, const CommandId&) = default;
};

/// The bus type of a C++ command type, as the schema converts it.
template <typename Command>
using BusOf = decltype(schema::toBus(std::declval<const Command&>(), 0));

/// An empty bus of `command_kind` (COMPLY_COMMAND_*).
CommandBus emptyBus(int command_kind) noexcept;
/// The bus as the plugin's step() takes it.
const void* busPointer(const CommandBus& bus) noexcept;
/// Copies the field groups `incoming` sets into `active` (same kind; otherwise nothing).
void mergeInto(CommandBus& active, const CommandBus& incoming) noexcept;
/// Motion reference = the measured pose at rest (and the nullspace target = measured joints).
void seedFromMeasured(CommandBus& bus, const MeasuredPose& measured) noexcept;
/// Rates (velocity, twist, acceleration) to zero: the reference holds where it is.
void stopMotion(CommandBus& bus) noexcept;
/// The measured pose held and nothing pushed: seedFromMeasured() and the feedforward wrench and
/// torque to zero (what a reset leaves in force).
void holdMeasured(CommandBus& bus, const MeasuredPose& measured) noexcept;
/// A Cartesian bus's reference along the force axes it selects onto the measured pose (task
/// frame; pipeline::anchorForceAxes), so that wherever those axes end (a command merged, the
/// watchdog, a chunk stopped) the arm is held where it is, not sprung back to a reference that was
/// never checked along them. A joint bus is left as it is.
void anchorForceAxes(CommandBus& bus, const MeasuredPose& measured) noexcept;

}  // namespace comply::pipeline
