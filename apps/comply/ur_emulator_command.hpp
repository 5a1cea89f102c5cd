#pragma once
// `comply ur-emulator`: a UR e-series controller emulated on the MuJoCo UR5e
// (comply/ur_emulator/ur_emulator.hpp), for `comply run --hardware ur` or any RTDE client
// without a robot. Runs until Ctrl-C or --duration.

#include <cstdint>
#include <iosfwd>
#include <string>

#include "emulator_serving.hpp"

namespace CLI {
class App;
}

namespace comply::app {

struct UrEmulatorCommandOptions {
  EmulatorCommonOptions common;  ///< address, scene, duration, priority (cycle and RTDE threads)
  std::uint16_t rtde_port = 30004;
  std::uint16_t script_port = 30002;
  std::uint16_t dashboard_port = 29999;
  std::string version = "5.23.0";
  double force_limit_n = 150.0;
  double unlock_delay_s = 5.0;
};

CLI::App* addUrEmulatorCommand(CLI::App& app, UrEmulatorCommandOptions& options);
/// Serves until stopped; a status line every second on `out`. 0, or 2 when it cannot start.
int urEmulatorCommand(const UrEmulatorCommandOptions& options, std::ostream& out,
                      std::ostream& err);

}  // namespace comply::app
