#pragma once
// The command side of `comply run`, off the control thread: every command taken from the command
// topics is accounted exactly once, as applied (by the cycle that took it) or rejected with its
// reason, and only one writer at a time may command the robot.
//
// A command passes, in order: well-formed (no joint vector longer than kMaxDof), the controller's
// kind, the publisher lock, an active controller, a stamp newer than the last accepted one (so
// that the stamp of the command in force names the newest command a cycle took), and the
// wrapper's own checks (Wrapper::submit). Accepted commands wait in `pending` until the control
// thread reports the stamp in force; the check-and-queue and the settling share one mutex, so a
// command is always pending before a cycle can take it.

#include <chrono>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include "comply/pipeline/wrapper.hpp"
#include "comply/transport/endpoints.hpp"
#include "live_observer.hpp"

namespace comply::host {

// The wire numbers the wrapper's reasons as the pipeline does: a verdict's reason is cast, here and
// in the ROS 2 controller.
static_assert(static_cast<int>(transport::Reason::kQueueFull) ==
                  static_cast<int>(pipeline::RejectionReason::kQueueFull) &&
              static_cast<int>(transport::Reason::kOutOfRange) ==
                  static_cast<int>(pipeline::RejectionReason::kOutOfRange) &&
              static_cast<int>(transport::Reason::kOtherPublisher) ==
                  static_cast<int>(pipeline::RejectionReason::kCount));

/// The writer that holds the command topics: the first to send, until it is silent for the
/// timeout (the controller's command_timeout_s, the watchdog's).
class PublisherLock {
 public:
  using Clock = std::chrono::steady_clock;
  explicit PublisherLock(double timeout_s) : timeout_s_(timeout_s) {}
  /// True when `publisher` may command now (it then holds the lock); otherwise `why`.
  bool admit(std::uint64_t publisher, Clock::time_point now, std::string& why);
  [[nodiscard]] std::uint64_t holder() const;

 private:
  double timeout_s_;
  mutable std::mutex mutex_;
  std::uint64_t holder_ = 0;
  Clock::time_point last_heard_{};
};

struct AccountingCounts {
  std::uint64_t received = 0;
  std::uint64_t applied = 0;
  std::uint64_t rejected = 0;
  std::vector<std::uint64_t> per_reason = std::vector<std::uint64_t>(transport::kReasonCount, 0);
};

class Accounting {
 public:
  /// Counts a command taken from a topic.
  void received();
  void reject(transport::CommandOutcomeMessage outcome, transport::Reason reason,
              std::string message);
  /// Stamp check, then `submit()` (returning a pipeline::Verdict) under the accounting lock.
  template <typename Submit>
  void submit(transport::CommandOutcomeMessage outcome, double stamp_s, Submit&& submit);
  /// The publisher thread: the commands up to `event.stamp_s` were applied by `event.cycle`.
  void settle(const AppliedEvent& event);
  /// Outcomes settled since the last call, in the order they were settled.
  std::vector<transport::CommandOutcomeMessage> takeOutcomes();
  /// At shutdown: the accepted commands no cycle took, rejected as kInactive.
  void abandonPending(const std::string& why);
  [[nodiscard]] AccountingCounts counts() const;
  [[nodiscard]] std::size_t pending() const;

 private:
  void rejectLocked(transport::CommandOutcomeMessage& outcome, transport::Reason reason,
                    std::string message);
  struct Pending {
    double stamp_s;
    transport::CommandOutcomeMessage outcome;
  };
  mutable std::mutex mutex_;
  AccountingCounts counts_;
  double last_accepted_s_ = -1.0;
  std::deque<Pending> pending_;
  std::vector<transport::CommandOutcomeMessage> settled_;
};

template <typename Submit>
void Accounting::submit(transport::CommandOutcomeMessage outcome, double stamp_s, Submit&& submit) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!(stamp_s > last_accepted_s_)) {
    rejectLocked(outcome, transport::Reason::kStaleStamp,
                 "stamp " + std::to_string(stamp_s) + " s is not newer than the last accepted " +
                     std::to_string(last_accepted_s_) + " s");
    return;
  }
  pending_.push_back({stamp_s, outcome});
  const pipeline::Verdict verdict = submit();
  if (!verdict.accepted) {
    pending_.pop_back();
    rejectLocked(outcome, static_cast<transport::Reason>(verdict.reason), verdict.message);
    return;
  }
  last_accepted_s_ = stamp_s;
}

/// Takes the samples of the command topics and the request topic and feeds the wrapper.
template <typename Command>
class Intake {
 public:
  Intake(pipeline::Wrapper<Command>& wrapper, LiveObserver<Command>& observer,
         Accounting& accounting, PublisherLock& lock)
      : wrapper_(wrapper), observer_(observer), accounting_(accounting), lock_(lock) {}

  void handle(const transport::Sample<transport::CartesianCommandMessage>& sample);
  void handle(const transport::Sample<transport::JointCommandMessage>& sample);
  void handle(const transport::Sample<transport::RequestMessage>& sample);

 private:
  template <typename Message>
  void command(const transport::Sample<Message>& sample, transport::WireCommandKind kind);

  pipeline::Wrapper<Command>& wrapper_;
  LiveObserver<Command>& observer_;
  Accounting& accounting_;
  PublisherLock& lock_;
};

extern template class Intake<CartesianCommand>;
extern template class Intake<JointCommand>;

}  // namespace comply::host
