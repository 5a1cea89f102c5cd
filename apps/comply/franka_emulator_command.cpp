// `comply franka-emulator` (franka_emulator_command.hpp).

#include "franka_emulator_command.hpp"

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <ostream>

#include "comply/franka/franka_errors.hpp"
#include "comply/franka_emulator/franka_emulator.hpp"
#include "stop_signal.hpp"

namespace comply::app {
namespace {

const char* modeName(franka::fci::RobotMode mode) {
  switch (mode) {
    case franka::fci::RobotMode::kOther:
      return "Other";
    case franka::fci::RobotMode::kIdle:
      return "Idle";
    case franka::fci::RobotMode::kMove:
      return "Move";
    case franka::fci::RobotMode::kGuiding:
      return "Guiding";
    case franka::fci::RobotMode::kReflex:
      return "Reflex";
    case franka::fci::RobotMode::kUserStopped:
      return "UserStopped";
    case franka::fci::RobotMode::kAutomaticErrorRecovery:
      return "AutomaticErrorRecovery";
  }
  return "?";
}

void printStatus(const franka::FrankaEmulator& emulator, std::ostream& out) {
  const franka::FrankaEmulatorStats stats = emulator.stats();
  const franka::FrankaEmulatorState state = emulator.state();
  out << "t " << static_cast<double>(state.time_ms) * 1e-3 << " s, " << modeName(state.mode)
      << (state.torque_control ? " (torque control)" : "") << ", motions " << stats.motions
      << ", answered " << stats.answered << ", late " << stats.late << ", lost " << stats.lost
      << " (longest run " << stats.longest_lost_run << "), reflexes " << stats.reflexes
      << (stats.last_reflex.empty() ? "" : " (last: " + stats.last_reflex + ")") << ", recoveries "
      << stats.recoveries << "\n"
      << std::flush;
}

int errorIndex(const std::string& name) {
  for (int index = 0; index < franka::fci::kErrorCount; ++index) {
    if (name == franka::errorName(index)) {
      return index;
    }
  }
  return -1;
}

}  // namespace

CLI::App* addFrankaEmulatorCommand(CLI::App& app, FrankaEmulatorCommandOptions& options) {
  CLI::App* command = app.add_subcommand(
      "franka-emulator",
      "a Franka robot's FCI (protocol 7) emulated on the MuJoCo FR3, for --hardware franka or "
      "libfranka programs without a robot");
  addEmulatorCommonOptions(*command, options.common, "its cycle");
  command->add_option("--command-port", options.command_port, "FCI command port (0: any free)")
      ->capture_default_str();
  command
      ->add_option("--lost-limit", options.lost_limit,
                   "states in a row without a command that end a motion")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  command
      ->add_option("--answer-wait", options.answer_wait_s,
                   "[s] a cycle waits for the client's command (0: not at all, as the robot); "
                   "longer: a busy host's scheduling loses no command (it counts as late)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 5.0));
  command->add_option("--reflex-at", options.reflex_at_s, "[s] a reflex then (0: none)");
  command->add_option("--reflex", options.reflex, "the reflex's error name")->capture_default_str();
  command->add_option("--lose-at", options.lose_at_s, "[s] commands lost then (0: none)");
  command->add_option("--lose-count", options.lose_count, "how many commands are lost")
      ->capture_default_str();
  return command;
}

int frankaEmulatorCommand(const FrankaEmulatorCommandOptions& options, std::ostream& out,
                          std::ostream& err) {
  const int reflex = errorIndex(options.reflex);
  if (reflex < 0) {
    err << "comply franka-emulator: --reflex '" << options.reflex
        << "' is not one of the robot's errors (joint_reflex, cartesian_reflex, ...)\n";
    return 2;
  }
  franka::FrankaEmulatorOptions emulator_options;
  emulator_options.address = options.common.address;
  emulator_options.command_port = options.command_port;
  emulator_options.lost_in_a_row_limit = options.lost_limit;
  emulator_options.answer_wait_s = options.answer_wait_s;
  emulator_options.priority = options.common.priority;
  emulator_options.scene = options.common.scene();
  const std::atomic<bool>& stop = stopOnSignals();
  franka::FrankaEmulator emulator(emulator_options);
  out << "comply franka-emulator: an FR3 (FCI protocol " << franka::fci::kProtocolVersion << ") on "
      << options.common.address << ":" << emulator.commandPort() << "\n"
      << std::flush;
  bool reflexed = false;
  bool lost = false;
  const auto inject = [&](double elapsed_s) {
    if (!reflexed && options.reflex_at_s > 0.0 && elapsed_s >= options.reflex_at_s) {
      emulator.reflex(reflex);
      reflexed = true;
      out << "comply franka-emulator: reflex " << options.reflex << "\n" << std::flush;
    }
    if (!lost && options.lose_at_s > 0.0 && elapsed_s >= options.lose_at_s) {
      emulator.loseCommands(options.lose_count);
      lost = true;
      out << "comply franka-emulator: the next " << options.lose_count << " commands lost\n"
          << std::flush;
    }
  };
  serveUntilStopped(stop, options.common.duration_s, std::chrono::milliseconds(20), inject,
                    [&] { printStatus(emulator, out); });
  return 0;
}

}  // namespace comply::app
