#pragma once
// The emulated Franka robot's inside (franka_emulator.hpp): one mutex over the plant and the
// robot's state, taken by its cycle, its command port and the tests' calls. The cycle thread
// alone reads the UDP socket.

#include <netinet/in.h>

#include <array>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "comply/franka_emulator/franka_emulator.hpp"
#include "comply/model/data.hpp"
#include "comply/model/model.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/sim/simulated_robot.hpp"

namespace comply::franka {

/// A motion the client asked for with Move.
struct EmulatedMotion {
  std::uint32_t id = 0;  ///< Move's command id: its responses carry it
  fci::MoveController controller = fci::MoveController::kExternal;
  fci::MoveGenerator generator = fci::MoveGenerator::kJointVelocity;
};

class FrankaEmulator::Impl {
 public:
  explicit Impl(const FrankaEmulatorOptions& options);
  ~Impl();

  void reflex(int error_index);
  void loseCommands(int count);
  void dropStates(int count);
  void push(const Vector6d& wrench);
  void closeConnection();
  FrankaEmulatorStats stats() const;
  FrankaEmulatorState state() const;
  void withPlant(const std::function<void(sim::SimulatedRobot&)>& edit);
  [[nodiscard]] std::uint16_t commandPort() const noexcept { return command_port_; }

 private:
  // fci_server.cpp: the command port (its own thread) and the UDP socket.
  void listen();
  void serve(const std::stop_token& stop);
  void serveClient(int client, const std::stop_token& stop);
  /// One request, with the mutex held; false ends the connection (a protocol error).
  bool handle(const fci::Header& header, std::span<const std::uint8_t> payload,
              const sockaddr_in& peer);
  bool handleConnect(const fci::Header& header, std::span<const std::uint8_t> payload,
                     const sockaddr_in& peer);
  void handleSetter(const fci::Header& header, std::span<const std::uint8_t> payload);
  void handleMove(const fci::Header& header, std::span<const std::uint8_t> payload);
  void handleRecovery(const fci::Header& header);
  /// A response on the command connection (any thread; its own lock for the socket).
  void respond(fci::Command command, std::uint32_t id, std::uint8_t status,
               std::uint16_t version = 0);
  void dropClient();

  // robot_cycle.cpp: one robot cycle (1 ms) and its parts, with the mutex held unless said.
  void runCycles(const std::stop_token& stop);
  /// Without the mutex: takes the client's commands in; waits (answer_wait_s) for the answer to
  /// the state sent last while a motion runs.
  void receiveCommands();
  void cycle();
  void startMotion();
  void endMotion(fci::MoveStatus status);
  void enterReflex(int error_index);
  void applyMotion(const fci::RobotCommandMessage* command);
  void holdArm();
  void checkReflexes();
  /// comply's model of the arm at the measured state (the robot's own model).
  void updateModel(model::Quantity quantities);
  void sendState();

  FrankaEmulatorOptions options_;
  model::RobotDescription robot_;
  model::Model model_;
  model::Data model_data_;
  std::unique_ptr<sim::SimulatedRobot> plant_;
  mutable std::mutex mutex_;

  // The command port.
  int listener_ = -1;
  std::uint16_t command_port_ = 0;
  std::mutex write_mutex_;  // the client socket's writes
  int client_ = -1;         // the connected client's socket (under mutex_ and write_mutex_)
  int udp_ = -1;
  sockaddr_in client_udp_{};
  bool streaming_ = false;  // a client connected: states go out

  // The robot.
  fci::RobotMode mode_ = fci::RobotMode::kIdle;
  std::optional<EmulatedMotion> pending_motion_;
  std::optional<EmulatedMotion> motion_;
  std::optional<std::uint32_t> recovery_id_;  // AutomaticErrorRecovery waiting for its end
  std::uint64_t recovery_end_ms_ = 0;
  std::array<bool, fci::kErrorCount> errors_{};
  std::array<bool, fci::kErrorCount> reflex_reason_{};
  fci::CollisionThresholds collision_;
  std::array<double, 7> joint_stiffness_{3000, 3000, 3000, 2500, 2500, 2000, 2000};  // N m/rad
  std::array<double, 7> joint_damping_{};  // critical for the arm's inertia at home [N m s/rad]
  std::array<double, 7> target_q_{};       // the joint impedance's target [rad]
  std::array<double, 7> commanded_torque_{};
  JointState measured_;
  Vector6d push_ = Vector6d::Zero();
  Vector6d external_wrench_ = Vector6d::Zero();  // on the tool this cycle: contact and push
  Eigen::Matrix<double, 7, 1> external_torque_ = Eigen::Matrix<double, 7, 1>::Zero();
  std::uint64_t time_ms_ = 0;
  int lose_ = 0;
  int drop_ = 0;

  // The cycle thread's: the client's newest command, and whether it answers the last state.
  fci::RobotCommandMessage command_;
  bool answered_ = false;
  std::uint64_t last_sent_id_ = 0;
  double last_send_s_ = 0.0;
  bool late_ = false;
  std::uint64_t lost_run_ = 0;
  std::array<bool, 100> success_{};  // the last 100 states of a motion: answered
  std::size_t success_at_ = 0;
  std::array<std::uint8_t, fci::kCommandBytes> datagram_{};
  std::array<std::uint8_t, fci::kStateBytes> outgoing_{};

  FrankaEmulatorStats stats_;
  std::jthread server_thread_;
  std::jthread cycle_thread_;
};

}  // namespace comply::franka
