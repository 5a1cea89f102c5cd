// Command intake for a live host (see live_intake.hpp).

#include "live_intake.hpp"

#include <array>
#include <tuple>
#include <type_traits>

#include "comply/core/clock.hpp"

namespace comply::host {
namespace {

/// A command or a chunk of the controller's kind (the gate refuses the other kind before it
/// asks). header.stamp is the stamp on every wire; what a transport left in stamp_s is not used,
/// so that the stamp the cycle reports in force is the one the gate accepted.
template <typename Command, typename Message>
pipeline::Verdict submitSample(pipeline::Wrapper<Command>& wrapper, const Message& message,
                               std::int64_t stamp_ns, std::int64_t clock_ns) {
  if constexpr (std::is_same_v<Message, transport::CommandMessageOf<Command>>) {
    Command command = message.command;
    command.stamp_s = stampSeconds(stamp_ns);
    return wrapper.submit(command, stamp_ns);
  } else if constexpr (std::is_same_v<Message, transport::ChunkMessageOf<Command>>) {
    Chunk<Command> chunk = message.chunk;
    chunk.stamp_s = stampSeconds(stamp_ns);
    return wrapper.submitChunk(chunk, stampSeconds(clock_ns), stamp_ns);
  } else {
    return {};  // unreachable
  }
}

template <typename Command, typename Message>
void offerSample(pipeline::Wrapper<Command>& wrapper, pipeline::CommandGate& gate,
                 const transport::Sample<Message>& sample, pipeline::CommandKind kind) {
  pipeline::Offer offer;
  offer.stamp_ns = sample.message.header.stamp.nanoseconds();
  offer.kind = kind;
  offer.publisher = sample.publisher;
  offer.participant = sample.participant;
  offer.sender = sample.sender;
  offer.malformed = sample.malformed;
  offer.malformed_reason = static_cast<pipeline::CommandReason>(sample.malformed_reason);
  offer.now_ns = monotonicNanoseconds();
  offer.clock_ns = wallClockNanoseconds();  // senders stamp with their wall clock (ROS 2 time)
  offer.nanosec = sample.message.header.stamp.nanosec;
  offer.chunk = std::is_same_v<Message, transport::CartesianChunkMessage> ||
                std::is_same_v<Message, transport::JointChunkMessage>;
  const bool active = wrapper.diagnostics().state != pipeline::WrapperState::kInactive;
  gate.offer(offer, active, [&](std::int64_t stamp_ns) {
    return submitSample(wrapper, sample.message, stamp_ns, offer.clock_ns);
  });
}

}  // namespace

template <typename Command>
template <typename Message>
void Intake<Command>::noteReceived(const transport::Sample<Message>& sample) {
  if (!sample.malformed.empty() || (recording_ == nullptr && view_ == nullptr)) {
    return;
  }
  const transport::Stamp now = transport::Stamp::now();
  if (recording_ != nullptr) {
    recording_->received(sample.message, now);
  }
  if (view_ != nullptr) {
    view_->received(sample.message, now);
  }
}

template <typename Command>
template <typename Message>
void Intake<Command>::handleCommand(const transport::Sample<Message>& sample) {
  noteReceived(sample);
  constexpr bool kCartesian = std::is_same_v<Message, transport::CartesianCommandMessage> ||
                              std::is_same_v<Message, transport::CartesianChunkMessage>;
  offerSample(wrapper_, gate_, sample,
              kCartesian ? pipeline::CommandKind::kCartesian : pipeline::CommandKind::kJoint);
}

/// The commands and chunks of one receive, merged by stamp: they come on different topics, and a
/// sender's stamps must increase across all of them. Each topic keeps its arrival order (a stamp
/// that went back on one topic is still refused as stale).
template <typename Command>
void Intake<Command>::take(const transport::Inbox& inbox) {
  const auto topics = inbox.commandTopics();
  std::array<std::size_t, std::tuple_size_v<decltype(topics)>> next{};
  while (true) {
    int first = -1;
    std::int64_t first_stamp = 0;
    transport::forEachTopic(topics, [&](int topic, const auto& samples) {
      if (next[topic] == samples.size()) {
        return;
      }
      const std::int64_t stamp = samples[next[topic]].message.header.stamp.nanoseconds();
      if (first < 0 || stamp < first_stamp) {
        first = topic;
        first_stamp = stamp;
      }
    });
    if (first < 0) {
      break;
    }
    transport::forEachTopic(topics, [&](int topic, const auto& samples) {
      if (topic == first) {
        handleCommand(samples[next[topic]++]);
      }
    });
  }
  for (const auto& sample : inbox.requests) {
    handleRequest(sample);
  }
  for (const std::uint64_t publisher : inbox.departed) {
    // A chunk of a sender that left does not start later, when no one is there to follow it up.
    if (const std::uint64_t chunk = gate_.releasePublisher(publisher); chunk != 0) {
      wrapper_.dropWaitingChunk(chunk);
    }
  }
}

template <typename Command>
void Intake<Command>::handleRequest(const transport::Sample<transport::RequestMessage>& sample) {
  noteReceived(sample);
  // Every request has an outcome, as every command has: its sender learns whether it was carried
  // out or why not.
  const std::int64_t stamp_ns = sample.message.header.stamp.nanoseconds();
  const std::uint32_t nanosec = sample.message.header.stamp.nanosec;
  const auto settle = [&](pipeline::CommandReason reason, std::string refusal) {
    gate_.settleRequest(stamp_ns, sample.sender, reason, std::move(refusal), nanosec);
  };
  // A malformed request (a frame_id over its bound, a type no host knows) still names its stamp
  // and sender: it is answered, refused for what it held, and is the last rejection too.
  if (!sample.malformed.empty()) {
    gate_.noteRefusal("request refused: " + sample.malformed);
    settle(static_cast<pipeline::CommandReason>(sample.malformed_reason), sample.malformed);
    return;
  }
  if (nanosec >= 1'000'000'000U) {
    const std::string why = "invalid_stamp: header.stamp.nanosec " + std::to_string(nanosec) +
                            " is out of range (0 to 999999999)";
    gate_.noteRefusal("request refused: " + why);
    settle(pipeline::CommandReason::kInvalidStamp, why);
    return;
  }
  if (sample.message.request == transport::RequestType::kProbe) {
    // Nothing to do, and nothing to refuse: a client that only reads sends it too.
    settle(pipeline::CommandReason::kNone, "");
    return;
  }
  // The publisher rule holds for requests too: while one process commands the arm, another
  // cannot deactivate or reset it. A refusal is also the diagnostics' last rejection.
  std::string why;
  if (!gate_.admitRequest(sample.participant, monotonicNanoseconds(), why)) {
    settle(pipeline::CommandReason::kOtherPublisher, why);
    return;
  }
  std::string refused;
  switch (sample.message.request) {
    case transport::RequestType::kActivate:
    case transport::RequestType::kDeactivate:
      // Settled once the control thread carried it out (or the activation failed).
      if (observer_.requestLifecycle(sample.message.request, stamp_ns, sample.sender)) {
        return;
      }
      refused = "too many activations and deactivations wait for the control thread";
      gate_.noteRefusal(refused);
      break;
    case transport::RequestType::kReset:
      // The robot's own recovery first (a reflex cleared), waited for: the cycle's reset is
      // refused while the robot stays stopped.
      if (hardware_ != nullptr) {
        if (const std::string why_not = hardware_->recover(); !why_not.empty()) {
          refused = "reset refused: the robot's error recovery failed: " + why_not;
          gate_.noteRefusal(refused);
          break;
        }
      }
      // Clears the stamp floor now; settled once the cycle has decided it.
      if (const std::uint64_t number = wrapper_.reset(); number != 0) {
        observer_.noteReset(number, stamp_ns, sample.sender);
        return;
      }
      refused = "reset: the intake queue is full, send it again";
      gate_.noteRefusal(refused);
      break;
    case transport::RequestType::kTare:
      if (const std::string why_not = wrapper_.tare(); !why_not.empty()) {
        refused = "tare: " + why_not;
        gate_.noteRefusal(refused);
      }
      break;
    case transport::RequestType::kProbe:
      break;  // answered above
  }
  settle(pipeline::CommandReason::kNone, refused);
}

template class Intake<CartesianCommand>;
template class Intake<JointCommand>;

}  // namespace comply::host
