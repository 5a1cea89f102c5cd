// JSON of the live messages (see live_json.hpp).

#include "live_json.hpp"

#include <cstdio>

namespace comply::app {

nlohmann::json toJson(const transport::Stamp& stamp) {
  return {{"sec", stamp.sec}, {"nanosec", stamp.nanosec}};
}

nlohmann::json toJson(const transport::ControllerStateMessage& s) {
  return {{"header", {{"stamp", toJson(s.header.stamp)}, {"frame_id", s.header.frame_id}}},
          {"state", toString(s.state)},
          {"command_kind", toString(s.command_kind)},
          {"cycle", s.cycle},
          {"joint_names", s.joint_names},
          {"position", s.position},
          {"velocity", s.velocity},
          {"effort", s.effort},
          {"torque_command", s.torque_command},
          {"tcp_position", s.tcp_position},
          {"tcp_orientation", s.tcp_orientation},
          {"tcp_twist", s.tcp_twist},
          {"reference_stamp", toJson(s.reference_stamp)},
          {"reference_fields", s.reference_fields},
          {"reference_position", s.reference_position},
          {"reference_orientation", s.reference_orientation},
          {"reference_joint_position", s.reference_joint_position},
          {"contact_wrench", s.contact_wrench},
          {"contact_wrench_source", toString(s.contact_wrench_source)},
          {"contact_wrench_tcp", s.contact_wrench_tcp},
          {"contact_wrench_task", s.contact_wrench_task},
          {"contact_wrench_bandwidth", s.contact_wrench_bandwidth_hz},
          {"passivity", s.passivity},
          {"tank_energy", s.tank_energy_j},
          {"nullspace_tank_energy", s.nullspace_tank_energy_j},
          {"energy_injected", s.energy_injected_j},
          {"energy_dissipated", s.energy_dissipated_j},
          {"energy_refused", s.energy_refused_j},
          {"gain_fraction", s.gain_fraction}};
}

nlohmann::json toJson(const transport::CommandOutcomeMessage& o) {
  return {{"stamp", toJson(o.stamp)},
          {"command_kind", toString(o.command_kind)},
          {"outcome", o.outcome == transport::Outcome::kApplied ? "applied" : "rejected"},
          {"reason", toString(o.reason)},
          {"cycle", o.cycle},
          {"received", toJson(o.received)},
          {"applied", toJson(o.applied)},
          {"message", o.message},
          {"sender", transport::toHex(o.sender)}};
}

nlohmann::json toJson(const transport::DiagnosticsMessage& d) {
  nlohmann::json rejections = nlohmann::json::object();
  for (std::size_t i = 0; i < d.rejections.size(); ++i) {
    rejections[std::string(toString(static_cast<transport::Reason>(i)))] = d.rejections[i];
  }
  nlohmann::json outcomes = nlohmann::json::array();
  for (const auto& outcome : d.outcomes) {
    outcomes.push_back(toJson(outcome));
  }
  return {{"header", {{"stamp", toJson(d.header.stamp)}, {"frame_id", d.header.frame_id}}},
          {"state", toString(d.state)},
          {"cycles", d.cycles},
          {"overruns", d.overruns},
          {"period", d.period_s},
          {"commands_received", d.commands_received},
          {"commands_applied", d.commands_applied},
          {"commands_rejected", d.commands_rejected},
          {"rejections", rejections},
          {"watchdog_timeouts", d.watchdog_timeouts},
          {"faults", d.faults},
          {"rate_limit_hits", d.rate_limit_hits},
          {"effort_limit_hits", d.effort_limit_hits},
          {"histogram_bin", d.histogram_bin_s},
          {"compute_time_histogram", d.compute_time_histogram},
          {"start_lateness_histogram", d.start_lateness_histogram},
          {"last_fault", d.last_fault},
          {"last_rejection", d.last_rejection},
          {"publisher", d.publisher},
          {"records_dropped", d.records_dropped},
          {"recording", d.recording},
          {"outcomes", outcomes}};
}

std::string outcomeLine(const transport::CommandOutcomeMessage& outcome) {
  char stamp[32];
  std::snprintf(stamp, sizeof(stamp), "%d.%09u", outcome.stamp.sec, outcome.stamp.nanosec);
  if (outcome.outcome == transport::Outcome::kApplied) {
    return std::string("applied ") + stamp + " by cycle " + std::to_string(outcome.cycle);
  }
  return std::string("rejected ") + stamp + ": " + std::string(toString(outcome.reason)) + ": " +
         outcome.message;
}

}  // namespace comply::app
