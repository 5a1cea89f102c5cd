// The UR backend's link thread: the RTDE connection, the program, reconnection (ur_link.hpp).

#include "ur_link.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <thread>

#include "comply/hardware/backend.hpp"
#include "comply/hardware/loop_clock.hpp"
#include "comply/ur/robot_status.hpp"

namespace comply::ur {
namespace {

constexpr const char* kLinkSilent =
    "the link to the UR controller is lost: no RTDE data within link_timeout_s";
constexpr const char* kLinkClosed =
    "the link to the UR controller is lost: the RTDE connection closed";
/// Silence this long [s] ends a connection that TCP still holds open: a new one is made.
constexpr double kSilenceBeforeReconnect_s = 1.0;
/// The program is sent again at most this often [s].
constexpr double kProgramRetry_s = 1.0;

std::string versionText(const ControllerVersion& v) {
  return std::to_string(v.major) + "." + std::to_string(v.minor) + "." + std::to_string(v.bugfix);
}

/// PolyScope 5.23 / 10.10 and later: torque_command and actual_current_as_torque.
bool hasTorqueInterface(const ControllerVersion& v) {
  return (v.major == 5 && v.minor >= 23) || (v.major == 10 && v.minor >= 10) || v.major > 10;
}

template <typename Value>
const Value& as(const std::vector<RtdeValue>& values, std::size_t index) {
  return std::get<Value>(values[index]);
}

}  // namespace

ControllerVersion UrArm::Link::connect() {
  const UrArmOptions& options = arm_.options_;
  const std::string where = options.robot_ip + ":" + std::to_string(options.rtde_port);
  try {
    auto client = std::make_unique<RtdeClient>(options.robot_ip, options.rtde_port,
                                               options.connect_timeout_s);
    const ControllerVersion version = client->controllerVersion();
    has_torque_ = hasTorqueInterface(version);
    if (options.program.mode == OutputMode::kTorque && !has_torque_) {
      throw hardware::BackendError(
          "UR: output.mode torque needs torque_command, which PolyScope 5.23 / 10.10 and later "
          "have; the controller at " +
          where + " runs " + versionText(version));
    }
    const int o = options.program.register_offset;
    std::vector<std::string> names{"timestamp",
                                   "actual_q",
                                   "actual_qd",
                                   "actual_TCP_force",
                                   "robot_mode",
                                   "safety_mode",
                                   "runtime_state",
                                   "output_int_register_" + std::to_string(o),
                                   "output_int_register_" + std::to_string(o + 1)};
    if (has_torque_) {
      names.emplace_back("actual_current_as_torque");
    }
    outputs_ = client->setupOutputs(1.0 / options.program.period_s, names);
    // The answers go over a connection of their own, which only the control thread writes: on
    // the one the link thread reads, a send would wait for the kernel's socket lock whenever
    // that thread (not real-time) holds it in a receive.
    auto commands = std::make_unique<RtdeClient>(options.robot_ip, options.rtde_port,
                                                 options.connect_timeout_s);
    std::vector<std::string> inputs{"input_int_register_" + std::to_string(o),
                                    "input_int_register_" + std::to_string(o + 1)};
    for (int joint = 0; joint < 6; ++joint) {
      inputs.push_back("input_double_register_" + std::to_string(o + joint));
    }
    inputs_ = commands->setupInputs(inputs);
    commands->start();
    client->start();
    client_ = std::move(client);
    commands_ = std::move(commands);
    arm_.input_recipe_.store(inputs_.id, std::memory_order_relaxed);
    arm_.socket_.store(commands_->socket(), std::memory_order_release);
    last_package_s_ = hardware::monotonicSeconds();
    connections_.fetch_add(1, std::memory_order_relaxed);
    return version;
  } catch (const RtdeError& error) {
    throw hardware::BackendError("UR at " + where + ": " + error.what());
  }
}

void UrArm::Link::startProgram(double timeout_s) {
  sendProgram();
  const double deadline_s = hardware::monotonicSeconds() + timeout_s;
  while (hardware::monotonicSeconds() < deadline_s) {
    if (receiveOnce(arm_.options_.link_timeout_s) && last_.stop == nullptr) {
      return;
    }
    if (!client_) {
      throw hardware::BackendError(std::string("UR: ") + kLinkClosed);
    }
  }
  std::string why = last_.stop != nullptr ? last_.stop : "no data package came";
  if (client_ && client_->otherRecipePackages() > 0) {
    why += " (" + std::to_string(client_->otherRecipePackages()) +
           " data packages of another recipe id came: the controller numbers its recipes "
           "otherwise than its set-up said)";
  }
  throw hardware::BackendError("UR: the control program did not start within " +
                               std::to_string(timeout_s) + " s: " + why);
}

void UrArm::Link::run(const std::stop_token& stop) {
  while (!stop.stop_requested()) {
    if (!client_) {
      tryReconnect();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      continue;
    }
    if (receiveOnce(arm_.options_.link_timeout_s)) {
      restartProgramIfStopped();
    } else if (client_ &&
               hardware::monotonicSeconds() - last_package_s_ > kSilenceBeforeReconnect_s) {
      lose(kLinkSilent);
    }
  }
}

bool UrArm::Link::receiveOnce(double timeout_s) {
  try {
    if (!client_->receive(values_, timeout_s)) {
      publishStop(kLinkSilent);
      return false;
    }
  } catch (const RtdeError&) {
    lose(kLinkClosed);
    return false;
  }
  publish();
  return true;
}

void UrArm::Link::publish() {
  const double period_s = arm_.options_.program.period_s;
  const std::uint64_t previous = last_.cycle;
  last_.time_s = as<double>(values_, 0);
  last_.cycle = static_cast<std::uint64_t>(std::llround(last_.time_s / period_s)) + 1;
  last_.arrived_s = hardware::monotonicSeconds();
  last_.q = as<std::array<double, 6>>(values_, 1);
  last_.dq = as<std::array<double, 6>>(values_, 2);
  last_.wrench = as<std::array<double, 6>>(values_, 3);
  if (has_torque_) {
    last_.tau = as<std::array<double, 6>>(values_, 9);
  } else {
    last_.tau.fill(std::numeric_limits<double>::quiet_NaN());
  }
  const auto robot_mode = as<std::int32_t>(values_, 4);
  const auto safety_mode = as<std::int32_t>(values_, 5);
  const auto runtime_state = as<std::uint32_t>(values_, 6);
  program_running_ = as<std::int32_t>(values_, 8) == 1 &&
                     runtime_state == static_cast<std::uint32_t>(RuntimeState::kPlaying);
  // Whatever the program does: powered, running, in normal safety.
  controller_ready_ =
      stopReason(robot_mode, safety_mode, static_cast<std::uint32_t>(RuntimeState::kPlaying),
                 true) == nullptr;
  last_.stop = stopReason(robot_mode, safety_mode, runtime_state, program_running_);
  if (previous != 0 && last_.cycle > previous + 1) {
    skipped_.fetch_add(last_.cycle - previous - 1, std::memory_order_relaxed);
  }
  last_package_s_ = last_.arrived_s;
  packages_.fetch_add(1, std::memory_order_relaxed);
  arm_.sample_.publishFromSoleWriter(last_);
  arm_.last_stop_.store(last_.stop, std::memory_order_release);
  arm_.newest_time_s_.store(last_.time_s, std::memory_order_release);
  arm_.newest_arrival_s_.store(last_.arrived_s, std::memory_order_release);
  arm_.received_.fetch_add(1, std::memory_order_acq_rel);
  const std::uint64_t one = 1;
  (void)::write(arm_.wakeup_, &one, sizeof one);
}

void UrArm::Link::publishStop(const char* why) {
  if (last_.stop == why) {
    return;
  }
  last_.stop = why;
  arm_.sample_.publishFromSoleWriter(last_);
  arm_.last_stop_.store(why, std::memory_order_release);
}

void UrArm::Link::lose(const char* why) {
  arm_.socket_.store(-1, std::memory_order_release);
  client_.reset();
  retired_ = std::move(commands_);
  program_running_ = false;
  last_attempt_s_ = hardware::monotonicSeconds();
  publishStop(why);
}

void UrArm::Link::tryReconnect() {
  const double now_s = hardware::monotonicSeconds();
  if (now_s - last_attempt_s_ < arm_.options_.reconnect_interval_s) {
    return;
  }
  last_attempt_s_ = now_s;
  try {
    (void)connect();
    last_program_s_ = -1e9;  // the program went with the link: sent on the first package
  } catch (const hardware::BackendError&) {
    client_.reset();  // tried again after the interval
    commands_.reset();
  }
}

void UrArm::Link::restartProgramIfStopped() {
  if (program_running_ || !controller_ready_) {
    return;
  }
  if (hardware::monotonicSeconds() - last_program_s_ < kProgramRetry_s) {
    return;
  }
  try {
    sendProgram();
  } catch (const std::exception&) {
    // Tried again after kProgramRetry_s; the stop stays published meanwhile.
  }
}

void UrArm::Link::sendProgram() {
  last_program_s_ = hardware::monotonicSeconds();
  // Registers a last session left on "drive" with its targets must not move the arm when the
  // program starts: they say "stand still" first.
  std::vector<RtdeValue> hold{std::int32_t{0}, std::int32_t{0}};
  for (int joint = 0; joint < 6; ++joint) {
    hold.emplace_back(0.0);
  }
  commands_->send(inputs_, hold);
  sendScript(arm_.options_.robot_ip, arm_.options_.script_port,
             controlProgramScript(arm_.options_.program), arm_.options_.connect_timeout_s);
  programs_.fetch_add(1, std::memory_order_relaxed);
}

UrLinkStats UrArm::Link::stats() const noexcept {
  UrLinkStats stats;
  stats.packages = packages_.load(std::memory_order_relaxed);
  stats.skipped_cycles = skipped_.load(std::memory_order_relaxed);
  stats.connections = connections_.load(std::memory_order_relaxed);
  stats.programs_sent = programs_.load(std::memory_order_relaxed);
  return stats;
}

void sendScript(const std::string& host, std::uint16_t port, const std::string& script,
                double timeout_s) {
  const std::string where = host + ":" + std::to_string(port);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  if (inet_pton(AF_INET, host.c_str(), &address.sin_addr) != 1) {
    throw hardware::BackendError("UR: \"" + host + "\" is not an IPv4 address");
  }
  const int socket = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  timeval limit{};
  limit.tv_sec = static_cast<time_t>(timeout_s);
  limit.tv_usec = static_cast<suseconds_t>((timeout_s - std::floor(timeout_s)) * 1e6);
  ::setsockopt(socket, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
  bool sent = socket >= 0 &&
              ::connect(socket, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  for (std::size_t at = 0; sent && at < script.size();) {
    const ssize_t n = ::send(socket, script.data() + at, script.size() - at, MSG_NOSIGNAL);
    sent = n > 0;
    at += sent ? static_cast<std::size_t>(n) : 0;
  }
  const std::string why = std::strerror(errno);
  if (socket >= 0) {
    ::shutdown(socket, SHUT_WR);
    ::close(socket);
  }
  if (!sent) {
    throw hardware::BackendError("UR: cannot send the control program to " + where +
                                 " (the secondary interface): " + why);
  }
}

}  // namespace comply::ur
