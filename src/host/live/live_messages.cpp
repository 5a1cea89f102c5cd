// Message builders for `comply run` (see live_messages.hpp).

#include "live_messages.hpp"

#include <cmath>
#include <sstream>

#include "comply/schema/schema.hpp"

namespace comply::host {
namespace {

transport::Stamp stampOf(double seconds) {
  return transport::Stamp::fromNanoseconds(static_cast<std::int64_t>(std::llround(seconds * 1e9)));
}

std::vector<double> vectorOf(const JointVector& values) {
  return {values.data(), values.data() + values.size()};
}

std::vector<std::uint64_t> binsOf(
    const std::array<std::atomic<std::uint64_t>, LoopCounters::kBins>& bins) {
  std::vector<std::uint64_t> values;
  values.reserve(bins.size());
  for (const auto& bin : bins) {
    values.push_back(bin.load(std::memory_order_relaxed));
  }
  return values;
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

}  // namespace

transport::HostState hostState(pipeline::WrapperState state) {
  switch (state) {
    case pipeline::WrapperState::kActive:
      return transport::HostState::kActive;
    case pipeline::WrapperState::kFault:
      return transport::HostState::kFault;
    case pipeline::WrapperState::kInactive:
      break;
  }
  return transport::HostState::kInactive;
}

transport::ControllerStateMessage stateMessage(const StateSample& sample,
                                               const pipeline::ResolvedController& resolved) {
  transport::ControllerStateMessage message;
  message.header = {sample.wall, resolved.robot.base_frame};
  message.state = hostState(sample.state);
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
  }
  message.reference_stamp = stampOf(sample.reference_stamp_s);
  message.reference_fields = sample.reference_fields;
  if (!resolved.cartesian()) {
    message.reference_joint_position = vectorOf(sample.reference_joint_position);
  }
  setPassivity(sample.passivity, message);
  return message;
}

transport::DiagnosticsMessage diagnosticsMessage(
    const pipeline::DiagnosticsSnapshot& wrapper, const LoopCounters& loop, double period_s,
    const pipeline::GateCounts& counts, std::uint64_t publisher, const std::string& host_name,
    std::vector<transport::CommandOutcomeMessage> outcomes) {
  transport::DiagnosticsMessage message;
  message.header = {transport::Stamp::now(), host_name};
  message.state = hostState(wrapper.state);
  message.cycles = loop.cycles.load(std::memory_order_relaxed);
  message.overruns = loop.overruns.load(std::memory_order_relaxed);
  message.period_s = period_s;
  message.commands_received = counts.received;
  message.commands_applied = counts.applied;
  message.commands_rejected = counts.rejected;
  message.rejections.assign(counts.per_reason.begin(), counts.per_reason.end());
  message.watchdog_timeouts = wrapper.watchdog_timeouts;
  message.faults = wrapper.faults;
  message.rate_limit_hits = wrapper.rate_limit_hits;
  message.effort_limit_hits = wrapper.effort_limit_hits;
  message.histogram_bin_s = LoopCounters::kBinSeconds;
  message.compute_time_histogram = binsOf(loop.compute);
  message.start_lateness_histogram = binsOf(loop.lateness);
  message.last_fault = wrapper.last_fault;
  message.last_rejection = wrapper.last_rejection;
  if (publisher != 0) {
    std::ostringstream text;
    text << std::hex << publisher;
    message.publisher = text.str();
  }
  message.outcomes = std::move(outcomes);
  return message;
}

}  // namespace comply::host
