// The emulated robot's command port and its UDP socket (franka_emulator.hpp).

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "comply/franka/fci_stream.hpp"
#include "emulator_impl.hpp"

namespace comply::franka {
namespace {

sockaddr_in addressOf(const std::string& address, std::uint16_t port) {
  sockaddr_in where{};
  where.sin_family = AF_INET;
  where.sin_port = htons(port);
  if (::inet_pton(AF_INET, address.c_str(), &where.sin_addr) != 1) {
    throw std::runtime_error("the Franka emulator's address '" + address +
                             "' is not an IPv4 address");
  }
  return where;
}

}  // namespace

void FrankaEmulator::Impl::listen() {
  const sockaddr_in where = addressOf(options_.address, options_.command_port);
  listener_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int one = 1;
  (void)::setsockopt(listener_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in bound{};
  socklen_t length = sizeof bound;
  if (listener_ < 0 ||
      ::bind(listener_, reinterpret_cast<const sockaddr*>(&where), sizeof where) != 0 ||
      ::listen(listener_, 4) != 0 ||
      ::getsockname(listener_, reinterpret_cast<sockaddr*>(&bound), &length) != 0) {
    const std::string why = std::strerror(errno);
    if (listener_ >= 0) {
      ::close(listener_);
    }
    throw std::runtime_error("the Franka emulator cannot listen on " + options_.address + ":" +
                             std::to_string(options_.command_port) + ": " + why);
  }
  command_port_ = ntohs(bound.sin_port);
  udp_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_in udp_where = where;
  udp_where.sin_port = 0;
  if (udp_ < 0 ||
      ::bind(udp_, reinterpret_cast<const sockaddr*>(&udp_where), sizeof udp_where) != 0) {
    throw std::runtime_error("the Franka emulator has no UDP socket on " + options_.address);
  }
}

void FrankaEmulator::Impl::serve(const std::stop_token& stop) {
  while (!stop.stop_requested()) {
    pollfd readable{listener_, POLLIN, 0};
    if (::poll(&readable, 1, 50) <= 0) {
      continue;
    }
    const int client = ::accept4(listener_, nullptr, nullptr, SOCK_CLOEXEC);
    if (client < 0) {
      continue;
    }
    serveClient(client, stop);  // one client at a time, as the robot takes one
    dropClient();
  }
}

void FrankaEmulator::Impl::serveClient(int client, const std::stop_token& stop) {
  sockaddr_in peer{};
  socklen_t length = sizeof peer;
  (void)::getpeername(client, reinterpret_cast<sockaddr*>(&peer), &length);
  {
    const std::lock_guard lock(mutex_);
    const std::lock_guard write_lock(write_mutex_);
    client_ = client;
  }
  std::array<std::uint8_t, fci::kHeaderBytes> header_bytes{};
  std::vector<std::uint8_t> payload;
  while (readExactly(client, header_bytes.data(), header_bytes.size(), stop)) {
    const fci::Header header = fci::getHeader(header_bytes);
    if (header.size < fci::kHeaderBytes || header.size > 4096) {
      return;
    }
    payload.resize(header.size - fci::kHeaderBytes);
    if (!readExactly(client, payload.data(), payload.size(), stop)) {
      return;
    }
    const std::lock_guard lock(mutex_);
    if (!handle(header, payload, peer)) {
      return;
    }
  }
}

void FrankaEmulator::Impl::dropClient() {
  const std::lock_guard lock(mutex_);
  if (motion_) {
    // The robot ends a motion whose client went away; there is nobody to tell.
    motion_.reset();
    holdArm();
  }
  pending_motion_.reset();
  recovery_id_.reset();
  streaming_ = false;
  const std::lock_guard write_lock(write_mutex_);
  if (client_ >= 0) {
    ::close(client_);
  }
  client_ = -1;
}

void FrankaEmulator::Impl::closeConnection() {
  const std::lock_guard write_lock(write_mutex_);
  if (client_ >= 0) {
    ::shutdown(client_, SHUT_RDWR);  // the server thread sees it closed and cleans up
  }
}

void FrankaEmulator::Impl::respond(fci::Command command, std::uint32_t id, std::uint8_t status,
                                   std::uint16_t version) {
  std::array<std::uint8_t, fci::kHeaderBytes + 3> message{};
  const std::size_t size = fci::kHeaderBytes + fci::responsePayloadBytes(command);
  fci::putHeader(std::span<std::uint8_t, fci::kHeaderBytes>(message.data(), fci::kHeaderBytes),
                 {command, id, static_cast<std::uint32_t>(size)});
  message[fci::kHeaderBytes] = status;
  std::memcpy(message.data() + fci::kHeaderBytes + 1, &version, sizeof version);
  const std::lock_guard write_lock(write_mutex_);
  if (client_ >= 0) {
    (void)::send(client_, message.data(), size, MSG_NOSIGNAL);
  }
}

bool FrankaEmulator::Impl::handle(const fci::Header& header, std::span<const std::uint8_t> payload,
                                  const sockaddr_in& peer) {
  if (static_cast<std::uint32_t>(header.command) >= fci::kCommandCount ||
      payload.size() != fci::requestPayloadBytes(header.command)) {
    return false;  // the robot closes a connection that is out of step
  }
  const bool connected = streaming_;
  if (header.command != fci::Command::kConnect && !connected) {
    return false;
  }
  switch (header.command) {
    case fci::Command::kConnect:
      return handleConnect(header, payload, peer);
    case fci::Command::kMove:
      handleMove(header, payload);
      return true;
    case fci::Command::kStopMove:
      if (motion_) {
        endMotion(fci::MoveStatus::kPreempted);
      }
      pending_motion_.reset();
      respond(header.command, header.command_id, 0);
      return true;
    case fci::Command::kSetCollisionBehavior:
    case fci::Command::kSetJointImpedance:
    case fci::Command::kSetCartesianImpedance:
    case fci::Command::kSetGuidingMode:
    case fci::Command::kSetEEToK:
    case fci::Command::kSetNEToEE:
    case fci::Command::kSetLoad:
      handleSetter(header, payload);
      return true;
    case fci::Command::kAutomaticErrorRecovery:
      handleRecovery(header);
      return true;
    case fci::Command::kLoadModelLibrary:
      respond(header.command, header.command_id, 1);  // kError: no model library served
      return true;
  }
  return false;
}

bool FrankaEmulator::Impl::handleConnect(const fci::Header& header,
                                         std::span<const std::uint8_t> payload,
                                         const sockaddr_in& peer) {
  std::uint16_t version = 0;
  std::uint16_t udp_port = 0;
  std::memcpy(&version, payload.data(), 2);
  std::memcpy(&udp_port, payload.data() + 2, 2);
  if (version != fci::kProtocolVersion) {
    respond(header.command, header.command_id,
            static_cast<std::uint8_t>(fci::ConnectStatus::kIncompatibleLibraryVersion),
            fci::kProtocolVersion);
    return true;
  }
  client_udp_ = peer;
  client_udp_.sin_port = htons(udp_port);
  streaming_ = true;
  ++stats_.connections;
  respond(header.command, header.command_id, 0, fci::kProtocolVersion);
  return true;
}

void FrankaEmulator::Impl::handleSetter(const fci::Header& header,
                                        std::span<const std::uint8_t> payload) {
  // The robot takes settings only between motions.
  const bool moving = motion_.has_value() || pending_motion_.has_value();
  bool valid = true;
  if (header.command == fci::Command::kSetCollisionBehavior && !moving) {
    collision_ =
        fci::getCollisionThresholds(std::span<const std::uint8_t, fci::kCollisionRequestBytes>(
            payload.data(), fci::kCollisionRequestBytes));
  } else if (header.command == fci::Command::kSetJointImpedance) {
    std::array<double, 7> stiffness{};
    std::memcpy(stiffness.data(), payload.data(), sizeof stiffness);
    for (const double k : stiffness) {
      valid = valid && std::isfinite(k) && k >= 0.0 && k <= 14250.0;
    }
    if (valid && !moving) {
      joint_stiffness_ = stiffness;
    }
  }
  // The others are taken; the emulator's plant does not use them.
  const auto status = moving  ? fci::SetterStatus::kRejected
                      : valid ? fci::SetterStatus::kSuccess
                              : fci::SetterStatus::kInvalidArgument;
  respond(header.command, header.command_id, static_cast<std::uint8_t>(status));
}

void FrankaEmulator::Impl::handleMove(const fci::Header& header,
                                      std::span<const std::uint8_t> payload) {
  const fci::MoveRequest move =
      fci::getMoveRequest(std::span<const std::uint8_t, fci::kMoveRequestBytes>(
          payload.data(), fci::kMoveRequestBytes));
  fci::MoveStatus refusal = fci::MoveStatus::kMotionStarted;
  if (mode_ == fci::RobotMode::kReflex || mode_ == fci::RobotMode::kUserStopped) {
    refusal = fci::MoveStatus::kRejectedBySafetyFunction;
  } else if (mode_ != fci::RobotMode::kIdle || motion_ || pending_motion_ ||
             // The emulator has no Cartesian motion generators nor Cartesian impedance.
             (move.generator != fci::MoveGenerator::kJointPosition &&
              move.generator != fci::MoveGenerator::kJointVelocity) ||
             move.controller == fci::MoveController::kCartesianImpedance) {
    refusal = fci::MoveStatus::kRejected;
  }
  if (refusal != fci::MoveStatus::kMotionStarted) {
    respond(header.command, header.command_id, static_cast<std::uint8_t>(refusal));
    return;
  }
  pending_motion_ = EmulatedMotion{header.command_id, move.controller, move.generator};
  respond(header.command, header.command_id,
          static_cast<std::uint8_t>(fci::MoveStatus::kMotionStarted));
}

void FrankaEmulator::Impl::handleRecovery(const fci::Header& header) {
  if (motion_ || pending_motion_) {
    respond(header.command, header.command_id,
            static_cast<std::uint8_t>(fci::RecoveryStatus::kRejected));
    return;
  }
  if (mode_ == fci::RobotMode::kUserStopped) {
    respond(header.command, header.command_id,
            static_cast<std::uint8_t>(fci::RecoveryStatus::kEmergencyAborted));
    return;
  }
  if (mode_ != fci::RobotMode::kReflex) {
    respond(header.command, header.command_id, 0);  // nothing to recover from
    return;
  }
  mode_ = fci::RobotMode::kAutomaticErrorRecovery;
  recovery_id_ = header.command_id;
  recovery_end_ms_ = time_ms_ + static_cast<std::uint64_t>(options_.recovery_s * 1e3);
}

}  // namespace comply::franka
