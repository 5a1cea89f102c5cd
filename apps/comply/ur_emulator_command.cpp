// `comply ur-emulator` (ur_emulator_command.hpp).

#include "ur_emulator_command.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <ostream>
#include <thread>

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
  command->add_option("--address", options.address, "IPv4 address to listen on")
      ->capture_default_str();
  command->add_option("--rtde-port", options.rtde_port, "RTDE (0: any free port)")
      ->capture_default_str();
  command->add_option("--script-port", options.script_port, "secondary interface (URScript)")
      ->capture_default_str();
  command->add_option("--dashboard-port", options.dashboard_port, "dashboard server")
      ->capture_default_str();
  command->add_option("--version", options.version, "PolyScope version it reports")
      ->capture_default_str();
  command->add_option("--object", options.objects, "MuJoCo fragment added to the world")
      ->check(CLI::ExistingFile);
  command->add_option("--tool", options.tool, "MuJoCo fragment on the TCP")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--force-limit", options.force_limit_n,
                   "TCP contact force [N] above which it makes a protective stop (0: none)")
      ->capture_default_str();
  command
      ->add_option("--unlock-delay", options.unlock_delay_s,
                   "[s] a protective stop lasts before the dashboard unlocks it")
      ->capture_default_str();
  command->add_option("--duration", options.duration_s, "[s] then stop (0: until Ctrl-C)");
  command
      ->add_option("--priority", options.priority,
                   "SCHED_FIFO priority of its cycle and RTDE threads, as a controller's are "
                   "real-time (0: normal; refused quietly where not permitted)")
      ->check(CLI::Range(0, 99));
  return command;
}

int urEmulatorCommand(const UrEmulatorCommandOptions& options, std::ostream& out,
                      std::ostream& err) {
  ur::UrEmulatorOptions emulator_options;
  emulator_options.address = options.address;
  emulator_options.rtde_port = options.rtde_port;
  emulator_options.script_port = options.script_port;
  emulator_options.dashboard_port = options.dashboard_port;
  emulator_options.protective_stop_force_n = options.force_limit_n;
  emulator_options.unlock_delay_s = options.unlock_delay_s;
  emulator_options.priority = options.priority;
  for (const std::string& object : options.objects) {
    emulator_options.scene.objects.emplace_back(object);
  }
  emulator_options.scene.tool = options.tool;
  try {
    emulator_options.version = parseVersion(options.version);
  } catch (const std::invalid_argument& error) {
    err << "comply ur-emulator: " << error.what() << "\n";
    return 2;
  }
  std::atomic<bool>& stop = stopOnSignals();
  ur::UrEmulator emulator(emulator_options);
  out << "comply ur-emulator: a UR5e controller (PolyScope " << options.version << ") on "
      << options.address << ": RTDE " << emulator.rtdePort() << ", secondary "
      << emulator.scriptPort() << ", dashboard " << emulator.dashboardPort() << "\n"
      << std::flush;
  const auto start = std::chrono::steady_clock::now();
  auto next_status = start + std::chrono::seconds(1);
  while (!stop.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const auto now = std::chrono::steady_clock::now();
    if (now >= next_status) {
      printStatus(emulator, out);
      next_status += std::chrono::seconds(1);
    }
    if (options.duration_s > 0.0 &&
        std::chrono::duration<double>(now - start).count() >= options.duration_s) {
      break;
    }
  }
  printStatus(emulator, out);
  return 0;
}

}  // namespace comply::app
