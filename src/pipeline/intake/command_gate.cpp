// The command gate (see command_gate.hpp).

#include "comply/pipeline/command_gate.hpp"

#include <cmath>
#include <sstream>
#include <utility>

#include "comply/core/clock.hpp"

namespace comply::pipeline {
std::string_view toString(CommandReason reason) {
  return rejectionReasonName(static_cast<std::size_t>(reason));
}

GateOptions gateOptions(const WrapperConfig& config, bool cartesian) {
  return {.kind = cartesian ? CommandKind::kCartesian : CommandKind::kJoint,
          .publisher_timeout_s = config.command_timeout_s,
          .max_stamp_lead_s = config.validation.max_stamp_lead_s};
}

CommandGate::CommandGate(GateOptions options) : options_(options) {}

CommandReason CommandGate::admitLocked(const Offer& offer, bool active, CommandOutcome& outcome) {
  ++counts_.received;
  outcome.stamp_ns = offer.stamp_ns;
  outcome.nanosec = offer.nanosec;
  outcome.kind = offer.kind;
  outcome.sender = offer.sender;
  outcome.received_ns = wallClockNanoseconds();
  if (!offer.malformed.empty()) {
    return rejectLocked(outcome, offer.malformed_reason, std::string(offer.malformed));
  }
  if (offer.kind != options_.kind) {
    return rejectLocked(outcome, CommandReason::kWrongKind,
                        std::string("this controller takes ") +
                            (options_.kind == CommandKind::kCartesian ? "Cartesian" : "joint") +
                            " commands");
  }
  const double silent_s = 1e-9 * static_cast<double>(offer.now_ns - holder_heard_ns_);
  // The holder is a sending process where the transport names it (its command and chunk writers
  // are one sender), else a writer.
  const bool holder_speaks = holder_ == offer.publisher ||
                             (offer.participant != 0 && offer.participant == holder_participant_);
  if (holder_ != 0 && !holder_speaks && silent_s <= options_.publisher_timeout_s) {
    std::ostringstream text;
    text << "publisher " << std::hex << holder_ << std::dec
         << " holds the command topics (last heard " << static_cast<int>(silent_s * 1000.0)
         << " ms ago); refused until it is silent for " << options_.publisher_timeout_s << " s";
    return rejectLocked(outcome, CommandReason::kOtherPublisher, text.str());
  }
  holder_ = offer.publisher;
  holder_participant_ = offer.participant;
  holder_heard_ns_ = offer.now_ns;
  if (!active) {
    return rejectLocked(outcome, CommandReason::kInactive,
                        "the controller is inactive (send an activate request)");
  }
  if (offer.nanosec >= 1'000'000'000U) {
    return rejectLocked(outcome, CommandReason::kInvalidStamp,
                        "header.stamp.nanosec " + std::to_string(offer.nanosec) +
                            " is out of range (0 to 999999999)");
  }
  const double lead_s = 1e-9 * static_cast<double>(offer.stamp_ns - offer.clock_ns);
  if (offer.clock_ns != 0 && lead_s > options_.max_stamp_lead_s) {
    std::ostringstream text;
    text << "stamp " << stampText(offer.stamp_ns) << " is " << lead_s
         << " s ahead of the host's clock " << stampText(offer.clock_ns) << " (at most "
         << options_.max_stamp_lead_s << " s: validation.max_stamp_lead_s)";
    return rejectLocked(outcome, CommandReason::kFutureStamp, text.str());
  }
  return CommandReason::kNone;
}

void CommandGate::acceptLocked(std::uint64_t sequence, CommandOutcome& outcome) {
  outcome.sequence = sequence;
  pending_.push_back({sequence, std::move(outcome)});
}

CommandReason CommandGate::rejectLocked(CommandOutcome& outcome, CommandReason reason,
                                        std::string message) {
  outcome.applied = false;
  outcome.reason = reason;
  outcome.message = std::move(message);
  // Named by its reason, as the wrapper names its own ("pose_jump: ..."), whoever refused it.
  const std::string reason_name(toString(reason));
  counts_.last_rejection = outcome.message.rfind(reason_name + ":", 0) == 0
                               ? outcome.message
                               : reason_name + ": " + outcome.message;
  ++counts_.rejected;
  ++counts_.per_reason.at(static_cast<std::size_t>(reason));
  settled_.push_back(std::move(outcome));
  return reason;
}

std::optional<std::int64_t> NotedChunk::hostNs(double controller_time_s) const noexcept {
  if (std::isnan(controller_time_s)) {
    return std::nullopt;
  }
  return host_ns + stampNanoseconds(controller_time_s - controller_s);
}

void CommandGate::attachChunksLocked() {
  while (const NotedChunk* next = chunks_.front()) {
    for (Pending& pending : pending_) {
      if (pending.sequence == next->timing.sequence) {
        pending.outcome.chunk = *next;
        break;
      }
    }
    chunks_.pop();
  }
}

void CommandGate::settle() {
  const std::lock_guard<std::mutex> lock(mutex_);
  while (const Applied* next = applied_.front()) {
    const Applied event = *next;
    // The records of that cycle and those before were noted before it (noteChunk first): the
    // outcomes it settles take theirs with them.
    attachChunksLocked();
    applied_.pop();
    while (!pending_.empty() && pending_.front().sequence <= event.sequence) {
      CommandOutcome& outcome = pending_.front().outcome;
      outcome.applied = true;
      outcome.reason = CommandReason::kNone;
      outcome.cycle = event.cycle;
      outcome.applied_ns = event.wall_ns;
      ++counts_.applied;
      settled_.push_back(std::move(outcome));
      pending_.pop_front();
    }
  }
  attachChunksLocked();  // a chunk superseded or dropped while it waited stays pending
}

void CommandGate::abandonPending(const std::string& why) {
  settle();
  const std::lock_guard<std::mutex> lock(mutex_);
  for (Pending& pending : pending_) {
    rejectLocked(pending.outcome, CommandReason::kInactive, why);
  }
  pending_.clear();
}

bool CommandGate::admitRequest(std::uint64_t participant, std::int64_t now_ns, std::string& why) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const double silent_s = 1e-9 * static_cast<double>(now_ns - holder_heard_ns_);
  if (holder_ == 0 || silent_s > options_.publisher_timeout_s ||
      (participant != 0 && participant == holder_participant_)) {
    return true;
  }
  std::ostringstream text;
  text << "request refused: publisher " << std::hex << holder_ << std::dec
       << " holds the command topics (last heard " << static_cast<int>(silent_s * 1000.0)
       << " ms ago); only its own process may send requests until it is silent for "
       << options_.publisher_timeout_s << " s";
  why = text.str();
  counts_.last_rejection = std::string(toString(CommandReason::kOtherPublisher)) + ": " + why;
  return false;
}

void CommandGate::settleRequest(std::int64_t stamp_ns, const SenderId& sender, CommandReason reason,
                                std::string refusal, std::uint32_t nanosec) {
  CommandOutcome outcome;
  outcome.stamp_ns = stamp_ns;
  outcome.nanosec = nanosec;
  outcome.kind = CommandKind::kRequest;
  outcome.sender = sender;
  outcome.received_ns = wallClockNanoseconds();
  outcome.applied = refusal.empty();
  outcome.reason = outcome.applied ? CommandReason::kNone : reason;
  outcome.applied_ns = outcome.applied ? outcome.received_ns : 0;
  outcome.message = std::move(refusal);
  const std::lock_guard<std::mutex> lock(mutex_);
  settled_.push_back(std::move(outcome));
}

void CommandGate::noteRefusal(std::string why) {
  const std::lock_guard<std::mutex> lock(mutex_);
  counts_.last_rejection = std::move(why);
}

std::uint64_t CommandGate::releasePublisher(std::uint64_t publisher) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (holder_ == publisher) {
    holder_ = 0;
  }
  if (chunk_publisher_ != publisher || publisher == 0) {
    return 0;
  }
  chunk_publisher_ = 0;
  return std::exchange(chunk_sequence_, 0);
}

std::vector<CommandOutcome> CommandGate::takeOutcomes() {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::vector<CommandOutcome> taken;
  taken.swap(settled_);
  return taken;
}

GateCounts CommandGate::counts() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return counts_;
}

std::size_t CommandGate::pending() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return pending_.size();
}

std::uint64_t CommandGate::publisher() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return holder_;
}

}  // namespace comply::pipeline
