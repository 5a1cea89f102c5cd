// comply's own FCI client (fci_session.hpp).

#include "comply/franka/fci_session.hpp"

#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

#include "comply/hardware/backend.hpp"
#include "comply/hardware/loop_clock.hpp"
#include "fci_command_channel.hpp"

namespace comply::franka {
namespace {

constexpr const char* kCommandLinkClosed = "the Franka robot closed the command connection";
constexpr const char* kNoState = "no state from the Franka robot in time";
constexpr const char* kSendFailed = "a torque command to the Franka robot could not be sent";

int udpSocket(std::uint16_t& port) {
  const int socket = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in any{};
  any.sin_family = AF_INET;
  any.sin_addr.s_addr = htonl(INADDR_ANY);
  socklen_t length = sizeof any;
  if (socket < 0 || ::bind(socket, reinterpret_cast<const sockaddr*>(&any), sizeof any) != 0 ||
      ::getsockname(socket, reinterpret_cast<sockaddr*>(&any), &length) != 0) {
    if (socket >= 0) {
      ::close(socket);
    }
    throw hardware::BackendError("no UDP port for the Franka robot's states");
  }
  port = ntohs(any.sin_port);
  return socket;
}

std::string moveStatusText(std::uint8_t status) {
  switch (static_cast<fci::MoveStatus>(status)) {
    case fci::MoveStatus::kSuccess:
      return "finished";
    case fci::MoveStatus::kMotionStarted:
      return "started";
    case fci::MoveStatus::kPreempted:
      return "preempted by another command";
    case fci::MoveStatus::kPreemptedBySafetyFunction:
    case fci::MoveStatus::kRejectedBySafetyFunction:
      return "refused: a safety function is active";
    case fci::MoveStatus::kRejected:
      return "refused: not possible now (is the robot in Idle, its joints unlocked?)";
    case fci::MoveStatus::kStartAtSingularPoseRejected:
      return "refused: the arm is at a singular pose";
    case fci::MoveStatus::kInvalidArgumentRejected:
      return "refused: an invalid argument";
    case fci::MoveStatus::kReflexAborted:
      return "ended by a reflex";
    case fci::MoveStatus::kEmergencyAborted:
      return "ended by the user stop";
    case fci::MoveStatus::kInputErrorAborted:
      return "ended: an invalid command";
    case fci::MoveStatus::kAborted:
      return "ended";
  }
  return "status " + std::to_string(status);
}

class FciSession final : public FrankaSession {
 public:
  explicit FciSession(const FciSessionOptions& options)
      : options_(options),
        channel_(options.robot_ip, options.command_port, options.connect_timeout_s) {
    std::uint16_t udp_port = 0;
    udp_ = udpSocket(udp_port);
    try {
      connect(udp_port);
    } catch (...) {
      ::close(udp_);  // no destructor runs for an object that was never made
      throw;
    }
  }

  ~FciSession() override {
    if (motion_id_ >= 0) {
      (void)stopTorqueControl();
    }
    ::close(udp_);
  }

  /// Connect: the protocol version checked, the UDP port named.
  void connect(std::uint16_t udp_port) {
    std::array<std::uint8_t, 4> connect{};
    std::memcpy(connect.data(), &fci::kProtocolVersion, 2);
    std::memcpy(connect.data() + 2, &udp_port, 2);
    FciResponse response;
    if (!channel_.await(channel_.send(fci::Command::kConnect, connect), options_.connect_timeout_s,
                        response)) {
      throw hardware::BackendError("the Franka robot at " + options_.robot_ip +
                                   " did not answer Connect");
    }
    version_ = response.version;
    if (response.status ==
        static_cast<std::uint8_t>(fci::ConnectStatus::kIncompatibleLibraryVersion)) {
      throw hardware::BackendError(
          "the Franka robot at " + options_.robot_ip + " speaks FCI protocol version " +
          std::to_string(version_) + "; comply's own client speaks " +
          std::to_string(fci::kProtocolVersion) +
          " (robot system 5.5): use --hardware-option client=libfranka with a libfranka for "
          "this robot");
    }
    if (response.status != 0) {
      throw hardware::BackendError("the Franka robot refused Connect (status " +
                                   std::to_string(response.status) + ")");
    }
  }

  bool read(FrankaSample& sample, double timeout_s) noexcept override {
    const double deadline_s = hardware::monotonicSeconds() + timeout_s;
    bool got = false;
    for (;;) {
      // Everything already in: the newest state counts (older ones were missed).
      for (Datagram datagram = receiveOne(); datagram != Datagram::kNone; datagram = receiveOne()) {
        got = got || datagram == Datagram::kNewState;
      }
      if (got) {
        break;
      }
      const double left_s = deadline_s - hardware::monotonicSeconds();
      if (left_s <= 0.0) {
        failure_ = channel_.closed() ? kCommandLinkClosed : kNoState;
        return false;
      }
      pollfd readable{udp_, POLLIN, 0};
      (void)::poll(&readable, 1, static_cast<int>(std::ceil(left_s * 1e3)));
    }
    failure_ = channel_.closed() ? kCommandLinkClosed : nullptr;
    toSample(sample);
    if (motion_id_ >= 0 && !sample.torque_control) {
      motion_id_ = -1;  // the robot ended it (a reflex, a stop): its Move response says how
    }
    return failure_ == nullptr;
  }

  bool writeTorque(std::span<const double, 7> torque_n_m) noexcept override {
    if (motion_id_ < 0) {
      return false;
    }
    command_.message_id = state_.message_id;
    command_.motion_finished = false;
    std::copy(torque_n_m.begin(), torque_n_m.end(), command_.tau_J_d.begin());
    return sendCommand();
  }

  [[nodiscard]] const char* failure() const noexcept override { return failure_; }

  std::string startTorqueControl(FrankaSample& first) override {
    if (motion_id_ >= 0) {
      toSample(first);
      return {};
    }
    std::array<std::uint8_t, fci::kMoveRequestBytes> payload{};
    fci::MoveRequest move;
    move.controller = fci::MoveController::kExternal;
    move.generator = fci::MoveGenerator::kJointVelocity;
    move.path_deviation = options_.path_deviation;
    move.goal_deviation = options_.path_deviation;
    fci::putMoveRequest(payload, move);
    const std::optional<std::uint32_t> sent = channel_.trySend(fci::Command::kMove, payload);
    FciResponse response;
    if (!sent) {
      return kCommandLinkClosed;
    }
    const std::uint32_t id = *sent;
    if (!channel_.await(id, options_.connect_timeout_s, response)) {
      return "no answer to Move";
    }
    if (response.status != static_cast<std::uint8_t>(fci::MoveStatus::kMotionStarted)) {
      return "the torque control was " + moveStatusText(response.status);
    }
    // The robot switches its modes within a few states; no torque goes out before.
    FrankaSample sample;
    for (int state = 0; state < 100; ++state) {
      if (!read(sample, 0.1)) {
        return failure_ != nullptr ? failure_ : kNoState;
      }
      if (sample.torque_control) {
        motion_id_ = id;
        first = sample;
        return {};
      }
      if (channel_.take(id, response)) {
        return "the torque control was " + moveStatusText(response.status);
      }
    }
    return "the robot did not switch to comply's torque control within 100 states";
  }

  std::string stopTorqueControl() override {
    if (motion_id_ < 0) {
      return {};
    }
    const auto id = static_cast<std::uint32_t>(motion_id_);
    motion_id_ = -1;
    command_.motion_finished = true;
    FrankaSample sample;
    for (int state = 0; state < 100; ++state) {
      command_.message_id = state_.message_id;
      (void)sendCommand();
      if (!read(sample, 0.1) || !sample.torque_control) {
        break;
      }
    }
    command_.motion_finished = false;
    command_.tau_J_d.fill(0.0);
    FciResponse response;
    if (!channel_.await(id, options_.connect_timeout_s, response)) {
      return "no answer when the torque control finished";
    }
    return response.status == 0 ? std::string()
                                : "the torque control " + moveStatusText(response.status);
  }

  std::string recover() override {
    FciResponse response;
    const std::optional<std::uint32_t> sent =
        channel_.trySend(fci::Command::kAutomaticErrorRecovery, {});
    if (!sent) {
      return kCommandLinkClosed;
    }
    if (!channel_.await(*sent, options_.connect_timeout_s, response)) {
      return "no answer to AutomaticErrorRecovery";
    }
    switch (static_cast<fci::RecoveryStatus>(response.status)) {
      case fci::RecoveryStatus::kSuccess:
        return {};
      case fci::RecoveryStatus::kManualRecoveryRequired:
        return "the robot needs a manual error recovery (Desk, or the external activation "
               "device pressed and released)";
      case fci::RecoveryStatus::kEmergencyAborted:
        return "the user stop is pressed";
      default:
        return "the robot refused the error recovery (status " + std::to_string(response.status) +
               ")";
    }
  }

  std::string setCollisionThresholds(const fci::CollisionThresholds& thresholds) override {
    std::array<std::uint8_t, fci::kCollisionRequestBytes> payload{};
    fci::putCollisionThresholds(payload, thresholds);
    FciResponse response;
    const std::optional<std::uint32_t> sent =
        channel_.trySend(fci::Command::kSetCollisionBehavior, payload);
    if (!sent) {
      return kCommandLinkClosed;
    }
    if (!channel_.await(*sent, options_.connect_timeout_s, response)) {
      return "no answer to SetCollisionBehavior";
    }
    switch (static_cast<fci::SetterStatus>(response.status)) {
      case fci::SetterStatus::kSuccess:
        return {};
      case fci::SetterStatus::kRejected:
        return "not possible now (a motion runs)";
      case fci::SetterStatus::kInvalidArgument:
        return "invalid thresholds";
      case fci::SetterStatus::kRejectedBySafetyFunction:
        return "a safety function is active";
    }
    return "status " + std::to_string(response.status);
  }

  [[nodiscard]] std::string description() const override {
    return "comply's FCI client, protocol version " + std::to_string(version_);
  }

 private:
  /// What receiveOne() found.
  enum class Datagram : std::uint8_t { kNone, kIgnored, kNewState };

  /// One datagram waiting, kept when it is a newer state than the last.
  Datagram receiveOne() noexcept {
    sockaddr_in from{};
    socklen_t length = sizeof from;
    const ssize_t got = ::recvfrom(udp_, datagram_.data(), datagram_.size(), MSG_DONTWAIT,
                                   reinterpret_cast<sockaddr*>(&from), &length);
    if (got < 0) {
      return Datagram::kNone;
    }
    if (got != static_cast<ssize_t>(fci::kStateBytes)) {
      return Datagram::kIgnored;  // not a state
    }
    const fci::RobotStateMessage state =
        fci::getRobotState(std::span<const std::uint8_t, fci::kStateBytes>(datagram_));
    if (state.message_id <= state_.message_id && have_state_) {
      return Datagram::kIgnored;  // an older one, overtaken
    }
    state_ = state;
    have_state_ = true;
    robot_ = from;
    arrived_s_ = hardware::monotonicSeconds();
    return Datagram::kNewState;
  }

  void toSample(FrankaSample& sample) const noexcept {
    sample.time_ms = state_.message_id;
    sample.arrived_s = arrived_s_;
    const auto copy = [&](fci::StateField field, auto& out) {
      const auto values = state_.field(field);
      std::copy(values.begin(), values.end(), out.begin());
    };
    copy(fci::StateField::kQ, sample.q);
    copy(fci::StateField::kDq, sample.dq);
    copy(fci::StateField::kTau_J, sample.tau_J);
    copy(fci::StateField::kO_F_ext_hat_K, sample.O_F_ext_hat_K);
    sample.robot_mode = state_.robot_mode;
    sample.torque_control = state_.controller == fci::ControllerMode::kExternal &&
                            state_.generator != fci::GeneratorMode::kIdle;
    sample.errors = state_.errors;
    sample.last_motion_errors = state_.reflex_reason;
    sample.command_success_rate = state_.control_command_success_rate;
  }

  bool sendCommand() noexcept {
    fci::putRobotCommand(outgoing_, command_);
    const ssize_t sent = ::sendto(udp_, outgoing_.data(), outgoing_.size(), 0,
                                  reinterpret_cast<const sockaddr*>(&robot_), sizeof robot_);
    if (sent != static_cast<ssize_t>(outgoing_.size())) {
      failure_ = kSendFailed;
      return false;
    }
    return true;
  }

  FciSessionOptions options_;
  FciCommandChannel channel_;
  int udp_ = -1;
  std::uint16_t version_ = 0;
  std::int64_t motion_id_ = -1;  // the running torque control's Move command id
  fci::RobotStateMessage state_;
  bool have_state_ = false;
  double arrived_s_ = 0.0;
  sockaddr_in robot_{};
  fci::RobotCommandMessage command_;
  std::array<std::uint8_t, fci::kStateBytes> datagram_{};
  std::array<std::uint8_t, fci::kCommandBytes> outgoing_{};
  const char* failure_ = nullptr;
};

}  // namespace

std::unique_ptr<FrankaSession> makeFciSession(const FciSessionOptions& options) {
  return std::make_unique<FciSession>(options);
}

}  // namespace comply::franka
