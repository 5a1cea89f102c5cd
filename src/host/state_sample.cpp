// Filling a StateSample after a cycle (see state_sample.hpp).

#include "comply/host/state_sample.hpp"

#include <cmath>
#include <optional>

#include "comply/model/update.hpp"
#include "comply/pipeline/command_bus_variant.hpp"
#include "comply/schema/schema.hpp"

namespace comply::host {
namespace {

std::vector<double> vectorOf(const JointVector& values) {
  return {values.data(), values.data() + values.size()};
}

void setPassivity(const pipeline::PassivitySnapshot& passivity,
                  transport::ControllerStateMessage& message) noexcept {
  message.passivity = passivity.enabled;
  message.tank_energy_j = passivity.tank_energy_j;
  message.nullspace_tank_energy_j = passivity.nullspace_tank_energy_j;
  message.energy_injected_j = passivity.injected_j;
  message.energy_dissipated_j = passivity.dissipated_j;
  message.energy_refused_j = passivity.refused_j;
  message.gain_fraction = passivity.gain_fraction;
}

/// The walls' distance and force of the last cycle (infinite before one ran: 0 then, as without
/// walls).
void setWalls(const pipeline::VirtualWalls& walls, StateSample& s) noexcept {
  s.walls = walls.enabled();
  s.wall_distance_m = s.walls && std::isfinite(walls.distance()) ? walls.distance() : 0.0;
  s.wall_force = walls.force();
  s.workspace_min = walls.box().min;
  s.workspace_max = walls.box().max;
}

/// The reflex's thresholds of the last cycle and its trip (all 0 while it is off).
void setReflex(const pipeline::ContactReflex& reflex, StateSample& s) noexcept {
  s.reflex = reflex.enabled();
  s.reflex_force_threshold = s.reflex ? reflex.inForce().force_n : Eigen::Vector3d::Zero();
  s.reflex_torque_threshold = s.reflex ? reflex.inForce().torque_nm : Eigen::Vector3d::Zero();
  s.reflex_tripped = reflex.tripped();
  s.reflex_reaction = transport::ReflexReaction::kNone;
  if (reflex.tripped()) {
    switch (reflex.config().reaction) {
      case pipeline::ReflexReaction::kHold:
        s.reflex_reaction = transport::ReflexReaction::kHold;
        break;
      case pipeline::ReflexReaction::kRetreat:
        s.reflex_reaction = transport::ReflexReaction::kRetreat;
        break;
      case pipeline::ReflexReaction::kFault:
        s.reflex_reaction = transport::ReflexReaction::kFault;
        break;
    }
  }
  s.reflex_wrench = reflex.wrench();
}

void copyReflex(const StateSample& sample, transport::ControllerStateMessage& message) noexcept {
  message.reflex = sample.reflex;
  for (int i = 0; i < 3; ++i) {
    message.reflex_force_threshold[i] = sample.reflex_force_threshold[i];
    message.reflex_torque_threshold[i] = sample.reflex_torque_threshold[i];
  }
  message.reflex_tripped = sample.reflex_tripped;
  message.reflex_reaction = sample.reflex_reaction;
  for (int i = 0; i < 6; ++i) {
    message.reflex_wrench[i] = sample.reflex_wrench[i];
  }
}

/// The contact-speed stage's limit, share and braking of the last cycle (0, 1, 0 while off).
void setContactSpeed(const pipeline::ContactSpeed& stage, StateSample& s) noexcept {
  s.contact_speed_limit_m_per_s = stage.limit();
  s.contact_speed_share = stage.share();
  s.contact_speed_brake_n = stage.brakeForce();
}

}  // namespace

transport::ControllerStateMessage stateMessage(const StateSample& sample,
                                               const pipeline::ResolvedController& resolved) {
  transport::ControllerStateMessage message;
  message.header = {sample.wall, resolved.config.base_frame};  // the model's: a file may set it
  message.state = sample.state;
  message.command_kind = resolved.cartesian() ? transport::WireCommandKind::kCartesian
                                              : transport::WireCommandKind::kJoint;
  message.cycle = sample.cycle;
  message.joint_names = resolved.config.joints;
  message.position = vectorOf(sample.joints.position);
  message.velocity = vectorOf(sample.joints.velocity);
  message.effort = vectorOf(sample.joints.effort);
  message.torque_command = vectorOf(sample.torque);
  for (int i = 0; i < 3; ++i) {
    message.tcp_position[i] = sample.tcp_position[i];
    message.reference_position[i] = sample.reference_position[i];
  }
  schema::toXyzw(sample.tcp_orientation, message.tcp_orientation.data());
  schema::toXyzw(sample.reference_orientation, message.reference_orientation.data());
  for (int i = 0; i < 6; ++i) {
    message.tcp_twist[i] = sample.tcp_twist[i];
    message.contact_wrench[i] = sample.contact_wrench[i];
    message.contact_wrench_tcp[i] = sample.contact_wrench_tcp[i];
    message.contact_wrench_task[i] = sample.contact_wrench_task[i];
  }
  message.contact_wrench_source = sample.contact_wrench_source;
  message.contact_wrench_bandwidth_hz = sample.contact_wrench_bandwidth_hz;
  message.reference_stamp = transport::Stamp::fromNanoseconds(sample.reference.stamp_ns);
  message.reference_sequence = sample.reference.sequence;
  message.reference_fields = sample.reference_fields;
  if (!resolved.cartesian()) {
    message.reference_joint_position = vectorOf(sample.reference_joint_position);
  }
  setPassivity(sample.passivity, message);
  message.walls = sample.walls;
  message.wall_distance_m = sample.wall_distance_m;
  for (int i = 0; i < 3; ++i) {
    message.wall_force[i] = sample.wall_force[i];
    message.workspace_min[i] = sample.workspace_min[i];
    message.workspace_max[i] = sample.workspace_max[i];
  }
  copyReflex(sample, message);
  message.contact_speed_limit_m_per_s = sample.contact_speed_limit_m_per_s;
  message.contact_speed_share = sample.contact_speed_share;
  message.contact_speed_brake_n = sample.contact_speed_brake_n;
  return message;
}

namespace {

/// The stamp as its sender wrote it: one whose nanosec is out of range (refused as invalid_stamp)
/// keeps its two fields, or the sender, matching them, would never find the outcome.
transport::Stamp sentStamp(const pipeline::CommandOutcome& outcome) {
  constexpr std::int64_t kSecond = 1'000'000'000;
  if (outcome.nanosec < kSecond) {
    return transport::Stamp::fromNanoseconds(outcome.stamp_ns);
  }
  return {static_cast<std::int32_t>((outcome.stamp_ns - outcome.nanosec) / kSecond),
          outcome.nanosec};
}

}  // namespace

transport::ChunkTimingMessage chunkTimingMessage(const pipeline::NotedChunk& noted) {
  const pipeline::ChunkTiming& timing = noted.timing;
  const auto host = [&](double controller_s) {
    const std::optional<std::int64_t> ns = noted.hostNs(controller_s);
    return ns ? transport::Stamp::fromNanoseconds(*ns) : transport::Stamp{};
  };
  transport::ChunkTimingMessage message;
  message.sequence = timing.sequence;
  message.end = static_cast<transport::ChunkEnd>(timing.end);
  message.observation = host(timing.observation_s);
  message.received = host(timing.received_s);
  message.takeover = host(timing.takeover_s);
  message.takeover_cycle = noted.cycle;
  message.requested_takeover = host(timing.requested_takeover_s);
  message.first_waypoint = host(timing.first_waypoint_s);
  message.last_waypoint = host(timing.last_waypoint_s);
  message.waypoints = static_cast<std::uint32_t>(timing.waypoints);
  message.waypoints_past = static_cast<std::uint32_t>(timing.waypoints_past);
  message.position_jump = timing.position_jump;
  message.rotation_jump = timing.rotation_jump;
  message.velocity_jump = timing.velocity_jump;
  message.angular_velocity_jump = timing.angular_velocity_jump;
  message.starved = timing.starved;
  message.rest_s = timing.rest_s;
  return message;
}

transport::CommandOutcomeMessage outcomeMessage(const pipeline::CommandOutcome& outcome) {
  transport::CommandOutcomeMessage message;
  message.stamp = sentStamp(outcome);
  switch (outcome.kind) {
    case pipeline::CommandKind::kCartesian:
      message.command_kind = transport::WireCommandKind::kCartesian;
      break;
    case pipeline::CommandKind::kJoint:
      message.command_kind = transport::WireCommandKind::kJoint;
      break;
    case pipeline::CommandKind::kRequest:
      message.command_kind = transport::WireCommandKind::kRequest;
      break;
  }
  message.outcome = outcome.applied ? transport::Outcome::kApplied : transport::Outcome::kRejected;
  message.reason = static_cast<transport::Reason>(outcome.reason);
  message.cycle = outcome.cycle;
  message.sequence_number = outcome.sequence;
  message.received = transport::Stamp::fromNanoseconds(outcome.received_ns);
  message.applied = transport::Stamp::fromNanoseconds(outcome.applied_ns);
  message.message = outcome.message;
  message.sender = outcome.sender;
  if (outcome.chunk) {
    message.chunk.push_back(chunkTimingMessage(*outcome.chunk));
  }
  return message;
}

std::vector<transport::CommandOutcomeMessage> outcomeMessages(
    const std::vector<pipeline::CommandOutcome>& outcomes) {
  std::vector<transport::CommandOutcomeMessage> messages;
  messages.reserve(outcomes.size());
  for (const pipeline::CommandOutcome& outcome : outcomes) {
    messages.push_back(outcomeMessage(outcome));
  }
  return messages;
}

template <typename Command>
StateSampler<Command>::StateSampler(const pipeline::Wrapper<Command>& wrapper)
    : wrapper_(wrapper), inactive_pose_(wrapper.controller().model()) {}

template <typename Command>
void StateSampler<Command>::fill(const hardware::CycleRecord& record, const JointState& measured,
                                 transport::Stamp stamp, StateSample& s) noexcept {
  const int dof = wrapper_.dof();
  s.cycle = record.index;
  s.wall = stamp;
  const pipeline::Controller& controller = wrapper_.controller();
  const pipeline::Diagnostics& diagnostics = controller.diagnostics();
  s.state = diagnostics.state.load(std::memory_order_relaxed);
  s.passivity = diagnostics.passivity();  // atomics only: no allocation on this thread
  setWalls(controller.walls(), s);
  setReflex(controller.reflex(), s);
  setContactSpeed(controller.contactSpeed(), s);
  s.joints = measured;
  s.torque.setZero(dof);
  for (std::size_t i = 0; i < record.torque.size(); ++i) {
    s.torque[static_cast<Eigen::Index>(i)] = record.wrote ? record.torque[i] : 0.0;
  }
  const model::Data* pose = &controller.modelData();
  if (s.state == pipeline::WrapperState::kInactive) {
    // No cycle measures while inactive: the sample must still show where the arm is.
    const std::span<const double> q(measured.position.data(),
                                    static_cast<std::size_t>(measured.position.size()));
    if (model::update(controller.model(), inactive_pose_, q, q, model::Quantity::kJacobian) ==
        model::UpdateStatus::kOk) {
      pose = &inactive_pose_;
    }
  }
  const model::Data& data = *pose;
  s.tcp_position = data.tip_position;
  s.tcp_orientation = data.tip_orientation;
  s.tcp_twist =
      data.jacobian.cols() == dof ? Vector6d(data.jacobian * s.joints.velocity) : Vector6d::Zero();
  // The observer's estimate when it runs (observer.enabled); else the wrist sensor's reading as
  // the cycle compensated it (the tool's weight and the tare off).
  if (const Vector6d* wrench = controller.contactWrench()) {
    const bool observer = wrench == &controller.observer().wrench();
    const pipeline::CycleParameters& parameters = controller.resolved().parameters;
    s.contact_wrench = *wrench;
    s.contact_wrench_source =
        observer ? transport::WrenchSource::kObserver : transport::WrenchSource::kSensor;
    s.contact_wrench_bandwidth_hz = observer ? parameters.observer.gain_per_s / (2.0 * M_PI)
                                             : parameters.wrench_sensor.filter_hz;
  } else {
    s.contact_wrench.setZero();
    s.contact_wrench_source = transport::WrenchSource::kNone;
    s.contact_wrench_bandwidth_hz = 0.0;
  }
  // The same wrench about the same point, in the TCP frame and in the task frame in force (the
  // frame a contact task's axes are named in, which turns with the task).
  const Eigen::Matrix3d tcp_rotation = s.tcp_orientation.toRotationMatrix();
  s.contact_wrench_tcp << tcp_rotation.transpose() * s.contact_wrench.head<3>(),
      tcp_rotation.transpose() * s.contact_wrench.tail<3>();
  // The task frame the law used (after the gain stage's slerp); the base frame under joint
  // control.
  s.contact_wrench_task = s.contact_wrench;
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    if (const auto* law = std::get_if<pipeline::BusOf<Command>>(&controller.lawBus())) {
      const Eigen::Matrix3d task = schema::fromXyzw(law->task_frame).toRotationMatrix();
      s.contact_wrench_task << task.transpose() * s.contact_wrench.head<3>(),
          task.transpose() * s.contact_wrench.tail<3>();
    }
  }
  s.reference_joint_position.setZero(dof);
  // The wrapper's kind is the bus's: get_if only because std::get may throw.
  const auto* bus = std::get_if<pipeline::BusOf<Command>>(&controller.activeCommand());
  if (bus == nullptr) {
    return;
  }
  s.reference = controller.idInForce();
  s.reference_fields = bus->fields;
  if constexpr (std::is_same_v<Command, CartesianCommand>) {
    s.reference_position = Eigen::Vector3d(bus->position[0], bus->position[1], bus->position[2]);
    s.reference_orientation = schema::fromXyzw(bus->orientation);
  } else {
    for (int i = 0; i < dof; ++i) {
      s.reference_joint_position[i] = bus->position[i];
    }
  }
}

template class StateSampler<CartesianCommand>;
template class StateSampler<JointCommand>;

}  // namespace comply::host
