// Stamps and the names of the message enumerations.

#include "comply/transport/messages.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "comply/core/clock.hpp"

namespace comply::transport {

Stamp Stamp::now() noexcept {
  return fromNanoseconds(wallClockNanoseconds());
}

Stamp Stamp::fromNanoseconds(std::int64_t nanoseconds) noexcept {
  const StampParts parts = splitStamp(std::clamp(nanoseconds, kMinNanoseconds, kMaxNanoseconds));
  return {static_cast<std::int32_t>(parts.sec), static_cast<std::uint32_t>(parts.nanosec)};
}

namespace {
constexpr double kSecondsEnd = 2147483648.0;  // 2^31: int32 seconds end just before it
}  // namespace

Stamp Stamp::fromSeconds(double seconds) noexcept {
  // Clamped before it becomes an integer: llround of a double past int64's range has no value.
  if (!(seconds >= -kSecondsEnd)) {  // NaN too
    return fromNanoseconds(kMinNanoseconds);
  }
  return seconds < kSecondsEnd ? fromNanoseconds(stampNanoseconds(seconds))
                               : fromNanoseconds(kMaxNanoseconds);
}

bool Stamp::holds(double seconds) noexcept {
  return seconds >= -kSecondsEnd && seconds < kSecondsEnd;  // false for NaN
}

std::string frameIdRefusal(std::string_view field, std::size_t bytes) {
  if (bytes <= static_cast<std::size_t>(kMaxFrameIdBytes)) {
    return {};
  }
  return std::string(field) + " is " + std::to_string(bytes) + " bytes, more than " +
         std::to_string(kMaxFrameIdBytes) + " (a frame's name)";
}

std::int64_t Stamp::nanoseconds() const noexcept {
  return static_cast<std::int64_t>(sec) * 1'000'000'000 + nanosec;
}

double Stamp::seconds() const noexcept {
  return stampSeconds(nanoseconds());
}

Stamp stampOrZero(double seconds) noexcept {
  return std::isnan(seconds) ? Stamp{} : Stamp::fromSeconds(seconds);
}

double secondsOrNaN(const Stamp& stamp) noexcept {
  return stamp == Stamp{} ? std::numeric_limits<double>::quiet_NaN() : stamp.seconds();
}

bool sentBy(const CommandOutcomeMessage& outcome, const Gid& sender) noexcept {
  return outcome.sender == sender || outcome.sender == Gid{};
}

bool answers(const CommittedMessage& answer, const Stamp& stamp, const Gid& sender) noexcept {
  return answer.request_stamp == stamp && (answer.sender == sender || answer.sender == Gid{});
}

std::string toHex(const Gid& gid) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text;
  text.reserve(2 * gid.size());
  for (const std::uint8_t byte : gid) {
    text += kDigits[byte >> 4U];
    text += kDigits[byte & 0x0fU];
  }
  return text;
}

std::string_view toString(WrenchSource source) {
  return nameIn(kWrenchSourceNames, source);
}

std::string_view toString(ReflexReaction reaction) {
  return nameIn(kReflexReactionNames, reaction);
}

std::string_view toString(WireCommandKind kind) {
  return nameIn(kWireCommandKindNames, kind);
}

std::string_view toString(Outcome outcome) {
  return nameIn(kOutcomeNames, outcome);
}

std::string_view toString(ChunkEnd end) {
  return nameIn(kChunkEndNames, end);
}

std::string_view toString(RequestType request) {
  return nameIn(kRequestTypeNames, request);
}

std::string_view toString(Reason reason) {
  return rejectionReasonName(static_cast<std::size_t>(reason));
}

template <>
CartesianCommand referenceInForce(const ControllerStateMessage& state, int dof) {
  CartesianCommand command = CartesianCommand::zero(dof);
  const auto& p = state.reference_position;
  const auto& q = state.reference_orientation;  // x y z w
  command.position = Eigen::Vector3d(p[0], p[1], p[2]);
  command.orientation = Eigen::Quaterniond(q[3], q[0], q[1], q[2]);
  return command;
}

template <>
JointCommand referenceInForce(const ControllerStateMessage& state, int dof) {
  JointCommand command = JointCommand::zero(dof);
  if (state.reference_joint_position.size() == static_cast<std::size_t>(dof)) {
    command.position =
        Eigen::Map<const Eigen::VectorXd>(state.reference_joint_position.data(), dof);
  }
  return command;
}

}  // namespace comply::transport
