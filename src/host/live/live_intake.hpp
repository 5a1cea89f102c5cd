#pragma once
// The command side of a live host, off the control thread: the samples of the command and request
// topics go through the command gate (pipeline/command_gate.hpp), which accounts for each one.

#include <string>
#include <vector>

#include "comply/hardware/hardware_interface.hpp"
#include "comply/host/host_recording.hpp"
#include "comply/pipeline/command_gate.hpp"
#include "comply/pipeline/wrapper.hpp"
#include "comply/transport/host_transport.hpp"
#include "comply/transport/messages.hpp"
#include "live_observer.hpp"

namespace comply::host {

// The wire numbers its reasons as the gate does.
static_assert(static_cast<int>(transport::Reason::kQueueFull) ==
                  static_cast<int>(pipeline::RejectionReason::kQueueFull) &&
              static_cast<int>(transport::Reason::kOutOfRange) ==
                  static_cast<int>(pipeline::RejectionReason::kOutOfRange) &&
              static_cast<int>(transport::Reason::kInvalidChunk) ==
                  static_cast<int>(pipeline::RejectionReason::kInvalidChunk) &&
              static_cast<int>(transport::Reason::kOtherPublisher) ==
                  static_cast<int>(pipeline::CommandReason::kOtherPublisher) &&
              static_cast<int>(transport::Reason::kWrongKind) ==
                  static_cast<int>(pipeline::CommandReason::kWrongKind) &&
              static_cast<int>(transport::Reason::kInactive) ==
                  static_cast<int>(pipeline::CommandReason::kInactive) &&
              transport::kReasonCount == pipeline::kCommandReasonCount);

/// Takes the samples of the command and chunk topics and the request topic and feeds the gate.
template <typename Command>
class Intake {
 public:
  /// A reset first runs `hardware`'s own recovery (HardwareInterface::recover; nullptr: none).
  Intake(pipeline::Wrapper<Command>& wrapper, LiveObserver<Command>& observer,
         pipeline::CommandGate& gate, hardware::HardwareInterface* hardware = nullptr)
      : wrapper_(wrapper), observer_(observer), gate_(gate), hardware_(hardware) {}

  /// One receive: its commands and chunks in stamp order, then its requests, then the writers
  /// that went away (they no longer hold the command topics).
  void take(const transport::Inbox& inbox);
  /// Every well-formed command and request is recorded as received (nullptr: none).
  void setRecording(HostRecording* recording) noexcept { recording_ = recording; }
  /// Every command and request is also shown there (nullptr: none).
  void setView(LiveView* view) noexcept { view_ = view; }

 private:
  /// A command or chunk of either kind: recorded as received, then offered to the gate.
  template <typename Message>
  void handleCommand(const transport::Sample<Message>& sample);
  template <typename Message>
  void noteReceived(const transport::Sample<Message>& sample);
  void handleRequest(const transport::Sample<transport::RequestMessage>& sample);

  pipeline::Wrapper<Command>& wrapper_;
  LiveObserver<Command>& observer_;
  pipeline::CommandGate& gate_;
  HostRecording* recording_ = nullptr;
  LiveView* view_ = nullptr;
  hardware::HardwareInterface* hardware_ = nullptr;
};

extern template class Intake<CartesianCommand>;
extern template class Intake<JointCommand>;

}  // namespace comply::host
