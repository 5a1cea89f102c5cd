#include "comply/pipeline/wrapper.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "comply/pipeline/command_bus.hpp"
#include "comply/pipeline/force_intake.hpp"
#include "comply/pipeline/reflex_intake.hpp"
#include "comply/schema/schema.hpp"

namespace comply::pipeline {
namespace {

template <typename Command>
constexpr int kKind =
    std::is_same_v<Command, CartesianCommand> ? COMPLY_COMMAND_CARTESIAN : COMPLY_COMMAND_JOINT;

std::shared_ptr<const ResolvedController> checkedKind(
    std::shared_ptr<const ResolvedController> resolved, int kind) {
  if (resolved->command_kind != kind) {
    const char* names[] = {"", "joint", "Cartesian"};
    throw plugin::PluginError(plugin::PluginErrc::kWrongCommandKind,
                              resolved->plugin->path().string() + " takes " +
                                  names[resolved->command_kind] + " commands, not " + names[kind]);
  }
  return resolved;
}

/// `full`: what filled up.
Verdict queueFull(const std::string& full) {
  return {false, RejectionReason::kQueueFull,
          std::string(toString(RejectionReason::kQueueFull)) + ": " + full +
              "; the sender is faster than the control rate"};
}

/// What a chunk may ask of this arm: the governor's speeds (applied at the intake whether or not
/// the governor runs in the cycle) and the blend a chunk starts with.
ChunkLimits chunkLimits(const ResolvedController& resolved) {
  const CycleParameters& p = resolved.parameters;
  return {.tcp_speed_m_per_s = p.governor.tcp_speed_m_per_s,
          .tcp_angular_speed_rad_per_s = p.governor.tcp_angular_speed_rad_per_s,
          .joint_speed = p.governed_speed,
          .blend_time_s = p.chunk_blend_time_s};
}

std::string commandsWaiting() {
  return std::to_string(Controller::kIntakeCapacity) + " commands already wait for the cycle";
}

}  // namespace

template <typename Command>
Wrapper<Command>::Wrapper(std::shared_ptr<const ResolvedController> resolved)
    : controller_(checkedKind(std::move(resolved), kKind<Command>)) {}

template <typename Command>
Wrapper<Command>::Wrapper(const WrapperConfig& config) : Wrapper(resolveController(config)) {}

template <typename Command>
std::uint64_t Wrapper<Command>::reset() {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  floor_ns_ = 0;  // a stamp that ran ahead locks no one out
  accepted_any_ = false;
  IntakeMessage message;
  message.type = IntakeMessage::Type::kReset;
  message.command = emptyBus(kKind<Command>);
  message.id.sequence = resets_ + 1;
  const std::uint64_t trips = controller_.diagnostics().reflex_trips.load();
  if (!controller_.enqueue(message)) {
    return 0;  // a full queue: the sender may send it again
  }
  reflex_trips_at_reset_ = trips;  // what follows it in the queue is taken after the reset
  return ++resets_;
}

template <typename Command>
void Wrapper<Command>::dropWaitingChunk(std::uint64_t sequence) {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  IntakeMessage message;
  message.type = IntakeMessage::Type::kDropChunk;
  message.command = emptyBus(kKind<Command>);
  message.id.sequence = sequence;
  // A full queue loses it: the chunk then starts, at most validation.max_stamp_lead_s late.
  (void)controller_.enqueue(message);
}

template <typename Command>
std::string Wrapper<Command>::tare() {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  if (!controller_.sensorSeen()) {
    return "the hardware has given no wrist force/torque reading: nothing to tare";
  }
  IntakeMessage message;
  message.type = IntakeMessage::Type::kTare;
  message.command = emptyBus(kKind<Command>);
  if (!controller_.enqueue(message)) {
    return commandsWaiting() + "; send the tare again";
  }
  return {};
}

template <typename Command>
typename Wrapper<Command>::IntakeStamp Wrapper<Command>::directStamp(double stamp_s) noexcept {
  const bool finite = std::isfinite(stamp_s);
  // Beyond about 292 years from the epoch the nanoseconds do not fit: such a stamp stands at the
  // end of the range (a later one cannot be newer, an earlier one is older).
  constexpr double kRangeS = 9.2e9;
  std::int64_t ns = 0;
  if (finite) {
    ns = stamp_s >= kRangeS    ? std::numeric_limits<std::int64_t>::max()
         : stamp_s <= -kRangeS ? std::numeric_limits<std::int64_t>::min()
                               : stampNanoseconds(stamp_s);
  }
  return {.ns = ns, .names_command = false, .finite = finite};
}

template <typename Command>
Verdict Wrapper<Command>::checkFloor(const IntakeStamp& stamp) const {
  if (!stamp.finite) {
    return {};  // the validation refuses it as non-finite
  }
  const auto stale = [](std::string why) {
    return Verdict{false, RejectionReason::kStaleStamp,
                   std::string(toString(RejectionReason::kStaleStamp)) + ": " + why};
  };
  if (stamp.names_command) {
    if (accepted_any_ && stamp.ns <= floor_ns_) {
      return stale("stamp " + stampText(stamp.ns) + " is not newer than the last accepted " +
                   stampText(floor_ns_));
    }
  } else if (stamp.ns < floor_ns_) {
    return stale("stamp is older than the last accepted command");
  }
  return {};
}

template <typename Command>
void Wrapper<Command>::accept(const IntakeStamp& stamp, const Command& gains, Verdict& verdict) {
  floor_ns_ = stamp.ns;
  accepted_any_ = true;
  verdict.sequence = ++last_sequence_;
  intake_gains_ = gains;
}

template <typename Command>
Verdict Wrapper<Command>::account(Verdict verdict, const IntakeStamp& stamp) {
  Diagnostics& diagnostics = controller_.diagnostics();
  if (verdict.accepted) {
    diagnostics.commands_accepted.fetch_add(1);
  } else if (!stamp.names_command) {
    diagnostics.rejections[static_cast<std::size_t>(verdict.reason)].fetch_add(1);
    diagnostics.setRejection("command rejected: ", verdict.message.c_str());
  }
  return verdict;
}

template <typename Command>
Verdict Wrapper<Command>::submit(const Command& command) {
  return submitStamped(command, directStamp(command.stamp_s));
}

template <typename Command>
Verdict Wrapper<Command>::submit(const Command& command, std::int64_t wire_stamp_ns) {
  return submitStamped(command, {.ns = wire_stamp_ns, .names_command = true});
}

template <typename Command>
Verdict Wrapper<Command>::submitStamped(const Command& command, const IntakeStamp& stamp) {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  if (Verdict stale = checkFloor(stamp); !stale.accepted) {
    return account(std::move(stale), stamp);
  }
  if (Verdict held = checkReflexLatch(controller_.diagnostics(), reflex_trips_at_reset_);
      !held.accepted) {
    return account(std::move(held), stamp);
  }
  const int dof = controller_.dof();
  const MeasuredPose measured = controller_.measuredPose();
  Command checked = Command::zero(dof);
  checked.stamp_s = -std::numeric_limits<double>::infinity();  // the floor is checked above
  // validateAndMerge() and, Cartesian, the force axes in force and the wrench bound.
  Verdict verdict = validateAtIntake(command, controller_, measured, intakeGains(), checked);
  if (verdict.accepted) {
    verdict = checkReflexCeilings(command, controller_.resolved().config.reflex);
  }
  Command gains = Command::zero(dof);
  if (verdict.accepted) {
    verdict = checkGains(command, command.fields, intakeGains(), measured.period_s, gains);
  }
  if (verdict.accepted) {
    IntakeMessage message;
    message.command = toBus(checked, dof);
    std::get<BusOf<Command>>(message.command).fields = static_cast<std::uint32_t>(command.fields);
    message.id = nextId(stamp);
    if (!controller_.enqueue(message)) {
      verdict = queueFull(commandsWaiting());
    } else {
      accept(stamp, gains, verdict);
    }
  }
  return account(std::move(verdict), stamp);
}

template <typename Command>
Command Wrapper<Command>::intakeGains() {
  if (!intake_gains_) {
    intake_gains_ = schema::fromBus(std::get<BusOf<Command>>(controller_.commandInForce()));
  }
  return *intake_gains_;
}

template <typename Command>
Verdict Wrapper<Command>::checkGains(const Command& command, CommandField fields,
                                     const Command& base, double period_s, Command& candidate) {
  candidate = base;
  Command incoming = command;
  incoming.fields = fields;
  schema::merge(candidate, incoming);
  Command checked = candidate;
  checked.fields = fields;
  return checkRenderable(checked, controller_.resolved().gain_bound, period_s);
}

template <typename Command>
Verdict Wrapper<Command>::submitChunk(const Chunk<Command>& chunk, double host_time_s) {
  return submitChunkStamped(chunk, host_time_s, directStamp(chunk.stamp_s));
}

template <typename Command>
Verdict Wrapper<Command>::submitChunk(const Chunk<Command>& chunk, double host_time_s,
                                      std::int64_t wire_stamp_ns) {
  return submitChunkStamped(chunk, host_time_s, {.ns = wire_stamp_ns, .names_command = true});
}

template <typename Command>
Verdict Wrapper<Command>::submitChunkStamped(const Chunk<Command>& chunk, double host_time_s,
                                             const IntakeStamp& stamp) {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  if (Verdict stale = checkFloor(stamp); !stale.accepted) {
    return account(std::move(stale), stamp);
  }
  if (Verdict held = checkReflexLatch(controller_.diagnostics(), reflex_trips_at_reset_);
      !held.accepted) {
    return account(std::move(held), stamp);
  }
  const int dof = controller_.dof();
  const MeasuredPose measured = controller_.measuredPose();
  Chunk<Command> checked = chunk;
  const ResolvedController& resolved = controller_.resolved();
  const CommandBus in_force = controller_.commandInForce();
  // A chunk that waits for its takeover starts from the reference the cycle will write then.
  std::optional<ChunkTakeover> takeover;
  if (std::isfinite(checked.takeover_s) && checked.takeover_s > host_time_s) {
    takeover = takeoverAt(checked.takeover_s, host_time_s, measured);
  }
  Verdict verdict =
      validateChunk(checked, resolved.config.validation, dof, measured,
                    -std::numeric_limits<double>::infinity(),  // floor: above
                    host_time_s, chunkLimits(resolved), &in_force, takeover ? &*takeover : nullptr);
  // Each waypoint's gains as the chunk reaches them, merged into what is in force before it.
  Command gains = intakeGains();
  for (const ChunkWaypoint<Command>& waypoint : checked.waypoints) {
    if (!verdict.accepted) {
      break;
    }
    const Command before = gains;
    verdict = checkGains(waypoint.command, checked.fields, before, measured.period_s, gains);
  }
  if (verdict.accepted) {
    // The last cycle ran at controller time measured.time_s; the host's clock reads host_time_s
    // somewhat later (less than a period when the cycle runs): the chunk then runs that early.
    const double host_to_controller_s = measured.time_s - host_time_s;
    ChunkPlayer& chunks = controller_.chunks();
    IntakeMessage message;
    message.type = IntakeMessage::Type::kChunk;
    message.command = emptyBus(kKind<Command>);
    message.id = nextId(stamp);
    message.chunk_slot = chunks.load(checked, host_to_controller_s, message.id.sequence,
                                     measured.time_s, takeover ? &takeover->reference : nullptr);
    if (message.chunk_slot < 0) {
      verdict =
          queueFull("all " + std::to_string(ChunkPlayer::kSlots) +
                    " chunk slots are taken (the chunk playing, those waiting for the cycle)");
    } else if (!controller_.enqueue(message)) {
      chunks.release(message.chunk_slot);
      verdict = queueFull(commandsWaiting());
    } else {
      accept(stamp, gains, verdict);
    }
  }
  return account(std::move(verdict), stamp);
}

template <typename Command>
bool Wrapper<Command>::predict(std::span<const double> times_s, double host_time_s,
                               std::vector<Command>& out) {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  std::vector<CommandBus> buses;
  const bool known = predictLocked(times_s, host_time_s, controller_.measuredPose(), buses);
  out.clear();
  out.reserve(buses.size());
  for (const CommandBus& bus : buses) {
    out.push_back(schema::fromBus(std::get<BusOf<Command>>(bus)));
  }
  return known;
}

template <typename Command>
bool Wrapper<Command>::predictLocked(std::span<const double> times_s, double host_time_s,
                                     const MeasuredPose& measured, std::vector<CommandBus>& out) {
  const double host_to_controller_s = measured.time_s - host_time_s;
  std::vector<double> controller_s(times_s.begin(), times_s.end());
  for (double& t : controller_s) {
    t += host_to_controller_s;
  }
  out.assign(times_s.size(), controller_.commandInForce());
  return controller_.chunks().predict(controller_s, measured.time_s, measured.period_s, out);
}

template <typename Command>
ChunkTakeover Wrapper<Command>::takeoverAt(double takeover_s, double host_time_s,
                                           const MeasuredPose& measured) {
  std::vector<CommandBus> reference;
  (void)predictLocked(std::span<const double>(&takeover_s, 1), host_time_s, measured, reference);
  ChunkTakeover takeover;
  takeover.time_s = takeover_s;
  takeover.reference = reference.front();
  takeover.pose = measured;
  const auto& bus = std::get<BusOf<Command>>(takeover.reference);
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    takeover.pose.tcp_position = Eigen::Map<const Eigen::Vector3d>(bus.position);
    takeover.pose.tcp_orientation = schema::fromXyzw(bus.orientation);
  } else {
    takeover.pose.position = Eigen::Map<const Eigen::VectorXd>(bus.position, bus.dof);
  }
  return takeover;
}

template <typename Command>
Command Wrapper<Command>::lastAccepted() const {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  using Bus = BusOf<Command>;
  return schema::fromBus(std::get<Bus>(controller_.commandInForce()));
}

template <typename Command>
MeasuredPose Wrapper<Command>::measuredPose() const {
  const std::lock_guard<std::mutex> lock(intake_mutex_);
  return controller_.measuredPose();
}

template class Wrapper<JointCommand>;
template class Wrapper<CartesianCommand>;

}  // namespace comply::pipeline
