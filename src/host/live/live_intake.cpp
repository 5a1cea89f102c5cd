// Command intake and accounting for `comply run` (see live_intake.hpp).

#include "live_intake.hpp"

#include <sstream>

namespace comply::host {

bool PublisherLock::admit(std::uint64_t publisher, Clock::time_point now, std::string& why) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const double silent_s = std::chrono::duration<double>(now - last_heard_).count();
  if (holder_ == 0 || holder_ == publisher || silent_s > timeout_s_) {
    holder_ = publisher;
    last_heard_ = now;
    return true;
  }
  std::ostringstream text;
  text << "publisher " << std::hex << holder_ << std::dec
       << " holds the command topics (last heard " << static_cast<int>(silent_s * 1000.0)
       << " ms ago); refused until it is silent for " << timeout_s_ << " s";
  why = text.str();
  return false;
}

std::uint64_t PublisherLock::holder() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return holder_;
}

void Accounting::received() {
  const std::lock_guard<std::mutex> lock(mutex_);
  ++counts_.received;
}

void Accounting::reject(transport::CommandOutcomeMessage outcome, transport::Reason reason,
                        std::string message) {
  const std::lock_guard<std::mutex> lock(mutex_);
  rejectLocked(outcome, reason, std::move(message));
}

void Accounting::rejectLocked(transport::CommandOutcomeMessage& outcome, transport::Reason reason,
                              std::string message) {
  outcome.outcome = transport::Outcome::kRejected;
  outcome.reason = reason;
  outcome.message = std::move(message);
  ++counts_.rejected;
  ++counts_.per_reason.at(static_cast<std::size_t>(reason));
  settled_.push_back(std::move(outcome));
}

void Accounting::settle(const AppliedEvent& event) {
  const std::lock_guard<std::mutex> lock(mutex_);
  while (!pending_.empty() && pending_.front().stamp_s <= event.stamp_s) {
    transport::CommandOutcomeMessage& outcome = pending_.front().outcome;
    outcome.outcome = transport::Outcome::kApplied;
    outcome.reason = transport::Reason::kNone;
    outcome.cycle = event.cycle;
    outcome.applied = event.wall;
    ++counts_.applied;
    settled_.push_back(std::move(outcome));
    pending_.pop_front();
  }
}

void Accounting::abandonPending(const std::string& why) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (Pending& pending : pending_) {
    rejectLocked(pending.outcome, transport::Reason::kInactive, why);
  }
  pending_.clear();
}

std::vector<transport::CommandOutcomeMessage> Accounting::takeOutcomes() {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::vector<transport::CommandOutcomeMessage> taken;
  taken.swap(settled_);
  return taken;
}

AccountingCounts Accounting::counts() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return counts_;
}

std::size_t Accounting::pending() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return pending_.size();
}

template <typename Command>
template <typename Message>
void Intake<Command>::command(const transport::Sample<Message>& sample,
                              transport::WireCommandKind kind) {
  accounting_.received();
  transport::CommandOutcomeMessage outcome;
  outcome.stamp = sample.message.header.stamp;
  outcome.command_kind = kind;
  outcome.received = transport::Stamp::now();
  std::string why;
  if (!sample.malformed.empty()) {
    accounting_.reject(outcome, transport::Reason::kDofMismatch, sample.malformed);
    return;
  }
  if constexpr (!std::is_same_v<decltype(sample.message.command), Command>) {
    accounting_.reject(outcome, transport::Reason::kWrongKind,
                       std::string("this controller takes ") +
                           (std::is_same_v<Command, CartesianCommand> ? "Cartesian" : "joint") +
                           " commands");
  } else {
    if (!lock_.admit(sample.publisher, PublisherLock::Clock::now(), why)) {
      accounting_.reject(outcome, transport::Reason::kOtherPublisher, why);
      return;
    }
    if (wrapper_.diagnostics().state == pipeline::WrapperState::kInactive) {
      accounting_.reject(outcome, transport::Reason::kInactive,
                         "the controller is inactive (send an activate request)");
      return;
    }
    const Command& command = sample.message.command;
    accounting_.submit(outcome, command.stamp_s, [&] { return wrapper_.submit(command); });
  }
}

template <typename Command>
void Intake<Command>::handle(const transport::Sample<transport::CartesianCommandMessage>& sample) {
  command(sample, transport::WireCommandKind::kCartesian);
}

template <typename Command>
void Intake<Command>::handle(const transport::Sample<transport::JointCommandMessage>& sample) {
  command(sample, transport::WireCommandKind::kJoint);
}

template <typename Command>
void Intake<Command>::handle(const transport::Sample<transport::RequestMessage>& sample) {
  switch (sample.message.request) {
    case transport::RequestType::kActivate:
    case transport::RequestType::kDeactivate:
      observer_.requestLifecycle(sample.message.request);
      break;
    case transport::RequestType::kReset:
      wrapper_.reset();
      break;
  }
}

template class Intake<CartesianCommand>;
template class Intake<JointCommand>;

}  // namespace comply::host
