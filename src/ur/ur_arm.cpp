// The UR backend's control-thread side: the newest sample, the answer written in place to the
// socket, and the clock on the controller's cycles (see ur_arm.hpp).

#include "comply/ur/ur_arm.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <thread>

#include "big_endian.hpp"
#include "comply/hardware/backend.hpp"
#include "ur_link.hpp"

namespace comply::ur {
namespace {

/// The answer's package: header (size, 'U'), recipe, cycle, drive, six doubles.
constexpr std::size_t kAnswerBytes = 3 + 1 + 4 + 4 + 6 * 8;

}  // namespace

UrArm::UrArm(UrArmOptions options) : options_(std::move(options)) {
  wakeup_ = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wakeup_ < 0) {
    throw hardware::BackendError("UR: cannot make an eventfd");
  }
  try {
    link_ = std::make_unique<Link>(*this);
    version_ = link_->connect();
    link_->startProgram(options_.connect_timeout_s);
    // The stops before the program ran (it had not started yet) are not the run's: the control
    // thread counts from here. Its side still, as the link thread has not started.
    sample_.update();
    stops_seen_ = sample_.read().stops;
  } catch (...) {
    link_.reset();
    ::close(wakeup_);
    throw;
  }
  // At normal priority, though a package waits for it before the cycle starts: measured with
  // the emulator on one 2-core host, SCHED_FIFO for it beside the control thread made cycles
  // later, not earlier (docs/ur.md, "Timing").
  link_thread_ = std::jthread([this](const std::stop_token& stop) { link_->run(stop); });
}

UrArm::~UrArm() {
  // Stand still now rather than keep the last velocity or torque until the program's watchdog
  // (the control thread has stopped: this is the only writer left).
  answered_ = false;
  (void)send(0, nullptr);
  std::this_thread::sleep_for(std::chrono::milliseconds(10));  // a few controller cycles
  link_thread_ = {};  // joins: the link is done before what it writes to goes
  link_.reset();
  ::close(wakeup_);
}

bool UrArm::read(JointState& state) noexcept {
  sample_.update();
  const UrSample& sample = sample_.read();
  if (sample.cycle == 0 || state.position.size() != 6) {
    return false;
  }
  for (int joint = 0; joint < 6; ++joint) {
    const auto j = static_cast<std::size_t>(joint);
    state.position[joint] = sample.q[j];
    state.velocity[joint] = sample.dq[j];
    state.effort[joint] = sample.tau[j];
  }
  answered_cycle_ = sample.cycle;
  answered_ = false;
  stop_ = sample.stop;
  if (sample.stops != stops_seen_) {
    stops_seen_ = sample.stops;
    stop_ = stop_ != nullptr ? stop_ : sample.last_stop;  // came and went since the last read
  }
  return true;
}

bool UrArm::readWrench(Vector6d& wrench) noexcept {
  const UrSample& sample = sample_.read();
  for (int i = 0; i < 6; ++i) {
    wrench[i] = sample.wrench[static_cast<std::size_t>(i)];
  }
  return sample.cycle != 0 && wrench.allFinite();
}

bool UrArm::readSequence(std::uint64_t& sequence) noexcept {
  sequence = sample_.read().cycle;
  return sequence != 0;
}

bool UrArm::write(std::span<const double> torque) noexcept {
  if (options_.program.mode != OutputMode::kTorque || torque.size() != 6) {
    return false;
  }
  JointVector values(6);  // capacity-bounded: no allocation (core/capacity.hpp)
  for (int joint = 0; joint < 6; ++joint) {
    values[joint] = torque[static_cast<std::size_t>(joint)];
  }
  return send(1, &values);
}

bool UrArm::writeCommand(const ActuatorCommand& command) noexcept {
  if (command.mode != options_.program.mode) {
    return false;
  }
  switch (command.mode) {
    case OutputMode::kPosition:
      return send(1, &command.position);
    case OutputMode::kVelocity:
      return send(1, &command.velocity);
    case OutputMode::kTorque:
      return send(1, &command.effort);
    default:
      return false;
  }
}

bool UrArm::hold() noexcept {
  // One answer per controller cycle: one already sent for this sample (a FAULT's command) stays,
  // so that the program does not apply whichever of two came first.
  return !answered_ && send(0, nullptr);
}

bool UrArm::send(int drive, const JointVector* values) noexcept {
  const int socket = socket_.load(std::memory_order_acquire);
  if (socket < 0 || (values != nullptr && (values->size() != 6 || !values->allFinite()))) {
    return false;
  }
  std::size_t at = wire::putAt(package_, 0, static_cast<std::uint16_t>(kAnswerBytes));
  package_[at++] = static_cast<std::uint8_t>(PackageType::kDataPackage);
  package_[at++] = input_recipe_.load(std::memory_order_relaxed);
  // The cycle's low 31 bits: the program compares it for a change only.
  at = wire::putAt(package_, at, static_cast<std::int32_t>(answered_cycle_ & 0x7fffffffU));
  at = wire::putAt(package_, at, static_cast<std::int32_t>(drive));
  for (int joint = 0; joint < 6; ++joint) {
    at = wire::putAt(package_, at, values != nullptr ? (*values)[joint] : 0.0);
  }
  // Never waits: a full send buffer means the link is failing, which the link thread reports. A
  // package that went out in part leaves the stream out of step: the link thread ends it.
  const ssize_t sent = ::send(socket, package_.data(), at, MSG_DONTWAIT | MSG_NOSIGNAL);
  if (sent > 0 && sent < static_cast<ssize_t>(at)) {
    answer_broken_.store(true, std::memory_order_release);
  }
  answered_ = sent == static_cast<ssize_t>(at);
  return answered_;
}

bool UrArm::awaitSample(double timeout_s) noexcept {
  const auto deadline = hardware::monotonicSeconds() + timeout_s;
  while (received_.load(std::memory_order_acquire) == awaited_) {
    const double left_s = deadline - hardware::monotonicSeconds();
    if (left_s <= 0.0) {
      return false;
    }
    pollfd readable{wakeup_, POLLIN, 0};
    const int milliseconds = static_cast<int>(std::ceil(left_s * 1e3));
    (void)::poll(&readable, 1, milliseconds);
    std::uint64_t count = 0;
    (void)::read(wakeup_, &count, sizeof count);  // clears it (non-blocking): the next poll waits
  }
  const std::uint64_t received = received_.load(std::memory_order_acquire);
  if (received > awaited_ + 1 && awaited_ != 0) {
    unanswered_.fetch_add(received - awaited_ - 1, std::memory_order_relaxed);
  }
  awaited_ = received;
  return true;
}

double UrArm::sampleTime() const noexcept {
  return newest_time_s_.load(std::memory_order_acquire);
}

double UrArm::sampleArrival() const noexcept {
  return newest_arrival_s_.load(std::memory_order_acquire);
}

UrLinkStats UrArm::stats() const noexcept {
  UrLinkStats stats = link_->stats();
  stats.unanswered = unanswered_.load(std::memory_order_relaxed);
  return stats;
}

std::string UrArm::summary() const {
  const UrLinkStats s = stats();
  return "UR link: " + std::to_string(s.packages) + " data packages, " +
         std::to_string(s.skipped_cycles) + " controller cycles without one, " +
         std::to_string(s.unanswered) + " left unanswered (a newer one had come), " +
         std::to_string(s.connections) + " connections, " + std::to_string(s.programs_sent) +
         " programs sent";
}

void UrClock::waitUntil(double time_s) noexcept {
  (void)time_s;  // the controller's cycle paces the loop, not a time of the host's
  (void)arm_.awaitSample(arm_.options().link_timeout_s);
}

double UrClock::lateness(double time_s) noexcept {
  (void)time_s;
  return hardware::monotonicSeconds() - arm_.sampleArrival();
}

}  // namespace comply::ur
