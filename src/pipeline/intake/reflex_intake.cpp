#include "comply/pipeline/reflex_intake.hpp"

#include <sstream>
#include <string>

namespace comply::pipeline {
namespace {

Verdict reject(RejectionReason reason, const std::string& message) {
  return {false, reason, std::string(toString(reason)) + ": " + message};
}

Verdict checkEntries(const char* field, const Eigen::Vector3d& value, double ceiling,
                     const char* option, const char* unit) {
  static constexpr const char* kAxes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (value[i] > ceiling) {
      std::ostringstream text;
      text << field << " along " << kAxes[i] << " is " << value[i] << " " << unit
           << ", above the ceiling " << option << " of " << ceiling << " " << unit
           << " (the controller file sets it)";
      return reject(RejectionReason::kOutOfRange, text.str());
    }
  }
  return {};
}

template <typename Command>
Verdict checkCeilings(const Command& command, const ReflexConfig& config) {
  if (!has(command.fields, CommandField::kReflex)) {
    return {};
  }
  Verdict verdict = checkEntries("reflex_force", command.reflex_force, config.max_force_n,
                                 "reflex.max_force_n", "N");
  if (verdict.accepted) {
    verdict = checkEntries("reflex_torque", command.reflex_torque, config.max_torque_nm,
                           "reflex.max_torque_nm", "N m");
  }
  return verdict;
}

}  // namespace

Verdict checkReflexLatch(const Diagnostics& diagnostics, std::uint64_t trips_at_reset) {
  if (!diagnostics.reflex_latched.load(std::memory_order_relaxed) ||
      diagnostics.reflex_trips.load(std::memory_order_relaxed) == trips_at_reset) {
    return {};
  }
  return reject(RejectionReason::kReflexLatched,
                "the contact reflex tripped and holds the arm (the state's reflex_tripped, "
                "reflex_wrench); an operator's reset request re-arms it and the arm resumes from "
                "where it is");
}

Verdict checkReflexCeilings(const CartesianCommand& command, const ReflexConfig& config) {
  return checkCeilings(command, config);
}

Verdict checkReflexCeilings(const JointCommand& command, const ReflexConfig& config) {
  return checkCeilings(command, config);
}

}  // namespace comply::pipeline
