// `comply ur-emulator` (ur_emulator_command.hpp).

#include "ur_emulator_command.hpp"

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <ostream>

#include "comply/ur/robot_status.hpp"
#include "comply/ur_emulator/ur_emulator.hpp"
#include "stop_signal.hpp"

namespace comply::app {
namespace {

ur::ControllerVersion parseVersion(const std::string& text) {
  ur::ControllerVersion version;
  unsigned major = 0;
  unsigned minor = 0;
  unsigned bugfix = 0;
  char end = 0;
  if (std::sscanf(text.c_str(), "%u.%u.%u%c", &major, &minor, &bugfix, &end) != 3) {
    throw std::invalid_argument("--version '" + text + "': expected MAJOR.MINOR.BUGFIX (5.23.0)");
  }
  version.major = major;
  version.minor = minor;
  version.bugfix = bugfix;
  return version;
}

void printStatus(const ur::UrEmulator& emulator, std::ostream& out) {
  const ur::UrEmulatorStats stats = emulator.stats();
  const ur::UrEmulatorState state = emulator.state();
  out << "t " << state.time_s << " s, " << ur::safetyModeName(state.safety_mode) << ", program "
      << (state.program_running ? ur::driveCommand(state.program_mode) : "stopped") << ", answered "
      << stats.answered << ", late " << stats.late << ", missed " << stats.missed
      << ", watchdog stops " << stats.watchdog_stops << ", protective stops "
      << stats.protective_stops << "\n"
      << std::flush;
}

}  // namespace

CLI::App* addUrEmulatorCommand(CLI::App& app, UrEmulatorCommandOptions& options) {
  CLI::App* command =
      app.add_subcommand("ur-emulator",
                         "a UR e-series controller emulated on the MuJoCo UR5e (RTDE, program, "
                         "dashboard), for --hardware ur without a robot");
  addEmulatorCommonOptions(*command, options.common,
                           "its cycle and RTDE threads, as a controller's are real-time");
  command->add_option("--rtde-port", options.rtde_port, "RTDE (0: any free port)")
      ->capture_default_str();
  command->add_option("--script-port", options.script_port, "secondary interface (URScript)")
      ->capture_default_str();
  command->add_option("--dashboard-port", options.dashboard_port, "dashboard server")
      ->capture_default_str();
  command->add_option("--version", options.version, "PolyScope version it reports")
      ->capture_default_str();
  command
      ->add_option("--force-limit", options.force_limit_n,
                   "TCP contact force [N] above which it makes a protective stop (0: none)")
      ->capture_default_str();
  command
      ->add_option("--unlock-delay", options.unlock_delay_s,
                   "[s] a protective stop lasts before the dashboard unlocks it")
      ->capture_default_str();
  return command;
}

int urEmulatorCommand(const UrEmulatorCommandOptions& options, std::ostream& out,
                      std::ostream& err) {
  ur::UrEmulatorOptions emulator_options;
  emulator_options.address = options.common.address;
  emulator_options.rtde_port = options.rtde_port;
  emulator_options.script_port = options.script_port;
  emulator_options.dashboard_port = options.dashboard_port;
  emulator_options.protective_stop_force_n = options.force_limit_n;
  emulator_options.unlock_delay_s = options.unlock_delay_s;
  emulator_options.priority = options.common.priority;
  emulator_options.scene = options.common.scene();
  try {
    emulator_options.version = parseVersion(options.version);
  } catch (const std::invalid_argument& error) {
    err << "comply ur-emulator: " << error.what() << "\n";
    return 2;
  }
  const std::atomic<bool>& stop = stopOnSignals();
  ur::UrEmulator emulator(emulator_options);
  out << "comply ur-emulator: a UR5e controller (PolyScope " << options.version << ") on "
      << options.common.address << ": RTDE " << emulator.rtdePort() << ", secondary "
      << emulator.scriptPort() << ", dashboard " << emulator.dashboardPort() << "\n"
      << std::flush;
  serveUntilStopped(
      stop, options.common.duration_s, std::chrono::milliseconds(50), [](double) {},
      [&] { printStatus(emulator, out); });
  return 0;
}

}  // namespace comply::app
