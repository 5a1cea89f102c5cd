// The UR backend's link thread: the RTDE connection, the program, reconnection (ur_link.hpp).

#include "ur_link.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
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
/// The answer connection's own output recipe [Hz]: only so that it may start.
constexpr double kCommandsOutputHz = 1.0;

std::string versionText(const ControllerVersion& v) {
  return std::to_string(v.major) + "." + std::to_string(v.minor) + "." + std::to_string(v.bugfix);
}

constexpr const char* kAnswerBroken =
    "the link to the UR controller is lost: an answer could not be sent whole";
constexpr const char* kStoppedOnRobot =
    "comply's control program was stopped on the robot, not by a stop comply recovers from: "
    "start comply run again";

/// PolyScope 5.23 / 10.10 and later: direct_torque.
bool hasTorqueCommand(const ControllerVersion& v) {
  return (v.major == 5 && v.minor >= 23) || (v.major == 10 && v.minor >= 10) || v.major > 10;
}

/// PolyScope 5.23 / 10.11 and later: actual_current_as_torque.
bool hasJointTorques(const ControllerVersion& v) {
  return (v.major == 5 && v.minor >= 23) || (v.major == 10 && v.minor >= 11) || v.major > 10;
}

/// The types the output recipe's variables have on every controller; a controller that says
/// otherwise is refused at set-up, so that reading a package cannot meet another type.
void checkTypes(const Recipe& recipe, const std::string& where) {
  for (std::size_t i = 0; i < recipe.names.size(); ++i) {
    const std::string& name = recipe.names[i];
    const RtdeType expected = name == "timestamp"           ? RtdeType::kDouble
                              : name == "runtime_state"     ? RtdeType::kUint32
                              : name.starts_with("actual_") ? RtdeType::kVector6d
                                                            : RtdeType::kInt32;
    if (recipe.types[i] != expected) {
      throw hardware::BackendError("UR at " + where + ": the controller gives " + name + " as " +
                                   std::string(nameIn(kRtdeTypeNames, recipe.types[i], "?")) +
                                   ", not " + std::string(nameIn(kRtdeTypeNames, expected, "?")));
    }
  }
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
    has_torque_ = hasJointTorques(version);
    if (options.program.mode == OutputMode::kTorque && !hasTorqueCommand(version)) {
      throw hardware::BackendError(
          "UR: output.mode torque needs direct_torque, which PolyScope 5.23 / 10.10 and later "
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
    checkTypes(outputs_, where);
    // The answers go over a connection of their own, which the control thread writes (this
    // thread only once, before the control thread runs): on the one this thread reads, a send
    // would wait for the kernel's socket lock whenever this thread (not real-time) held it.
    auto commands = std::make_unique<RtdeClient>(options.robot_ip, options.rtde_port,
                                                 options.connect_timeout_s);
    std::vector<std::string> inputs{"input_int_register_" + std::to_string(o),
                                    "input_int_register_" + std::to_string(o + 1)};
    for (int joint = 0; joint < 6; ++joint) {
      inputs.push_back("input_double_register_" + std::to_string(o + joint));
    }
    inputs_ = commands->setupInputs(inputs);
    // An output recipe as well, which a controller may require to start a connection; slow, and
    // drained by this thread (drainCommands).
    (void)commands->setupOutputs(kCommandsOutputHz, {"timestamp"});
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
  sendProgram(true);
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
    try {
      if (!client_) {
        tryReconnect();
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
        continue;
      }
      if (arm_.answer_broken_.exchange(false, std::memory_order_acq_rel)) {
        lose(kAnswerBroken);
        continue;
      }
      if (receiveOnce(arm_.options_.link_timeout_s)) {
        drainCommands();
        restartProgramIfStopped();
      } else if (client_ &&
                 hardware::monotonicSeconds() - last_package_s_ > kSilenceBeforeReconnect_s) {
        lose(kLinkSilent);
      }
    } catch (const std::exception&) {
      // Whatever the controller sent that this side cannot take ends the link, not the process.
      lose(kLinkClosed);
    }
  }
}

void UrArm::Link::drainCommands() {
  if (!commands_) {
    return;
  }
  try {
    while (commands_->receive(scratch_, 0.0)) {
    }
  } catch (const RtdeError&) {
    lose(kLinkClosed);
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
  const char* const previous_stop = last_.stop;
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
  const auto program_flag = as<std::int32_t>(values_, 8);
  program_running_ = program_flag == instance_ &&
                     runtime_state == static_cast<std::uint32_t>(RuntimeState::kPlaying);
  // Whatever the program does: powered, running, in normal safety.
  controller_ready_ =
      stopReason(robot_mode, safety_mode, static_cast<std::uint32_t>(RuntimeState::kPlaying),
                 true) == nullptr;
  // The program is sent again only after a stop comply recovers from: a safety stop, a lost
  // link (lose()), its own watchdog. One stopped on the pendant stays stopped.
  if (!controller_ready_ || program_flag == -instance_) {
    restart_allowed_ = true;
  }
  seen_running_ = seen_running_ || program_running_;
  last_.stop = stopReason(robot_mode, safety_mode, runtime_state, program_running_);
  if (last_.stop != nullptr && controller_ready_ && seen_running_ && !restart_allowed_) {
    last_.stop = kStoppedOnRobot;
  }
  if (previous != 0 && last_.cycle > previous + 1) {
    skipped_.fetch_add(last_.cycle - previous - 1, std::memory_order_relaxed);
  }
  last_package_s_ = last_.arrived_s;
  packages_.fetch_add(1, std::memory_order_relaxed);
  noteStop(previous_stop);
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
  const char* const previous_stop = last_.stop;
  last_.stop = why;
  noteStop(previous_stop);
  arm_.sample_.publishFromSoleWriter(last_);
  arm_.last_stop_.store(why, std::memory_order_release);
}

void UrArm::Link::noteStop(const char* previous) {
  if (last_.stop != nullptr && last_.stop != previous) {
    ++last_.stops;
    last_.last_stop = last_.stop;
  }
}

void UrArm::Link::lose(const char* why) {
  arm_.socket_.store(-1, std::memory_order_release);
  client_.reset();
  if (commands_) {
    commands_->disconnect();  // the controller frees its registers for the next connection
  }
  retired_ = std::move(commands_);
  program_running_ = false;
  restart_allowed_ = true;
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
  if (program_running_ || !controller_ready_ || !restart_allowed_) {
    return;
  }
  if (hardware::monotonicSeconds() - last_program_s_ < kProgramRetry_s) {
    return;
  }
  try {
    sendProgram(false);
  } catch (const std::exception&) {
    // Tried again after kProgramRetry_s; the stop stays published meanwhile.
  }
}

void UrArm::Link::sendProgram(bool write_hold) {
  last_program_s_ = hardware::monotonicSeconds();
  if (write_hold) {
    // Before the control thread answers (the first program): registers a last session left on
    // "drive" with its targets must not move the arm when the program starts. Later the control
    // thread's answers are in them (in a FAULT, its hold at the measured pose).
    std::vector<RtdeValue> hold{std::int32_t{0}, std::int32_t{0}};
    for (int joint = 0; joint < 6; ++joint) {
      hold.emplace_back(0.0);
    }
    commands_->send(inputs_, hold);
  }
  ControlProgram program = arm_.options_.program;
  instance_ = instance_ % 2147483646 + 1;
  program.instance = instance_;
  restart_allowed_ = false;
  seen_running_ = false;
  sendScript(arm_.options_.robot_ip, arm_.options_.script_port, controlProgramScript(program),
             arm_.options_.connect_timeout_s);
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

}  // namespace comply::ur
