#pragma once
// `comply franka-emulator`: a Franka robot's FCI emulated on the MuJoCo FR3
// (comply/franka_emulator/franka_emulator.hpp), for `comply run --hardware franka` or any
// libfranka program without a robot. Runs until Ctrl-C or --duration.

#include <cstdint>
#include <iosfwd>
#include <string>

#include "emulator_serving.hpp"

namespace CLI {
class App;
}

namespace comply::app {

struct FrankaEmulatorCommandOptions {
  EmulatorCommonOptions common;  ///< address, scene, duration, priority (of its cycle)
  std::uint16_t command_port = 1337;
  int lost_limit = 20;         ///< states in a row without a command
  double answer_wait_s = 0.0;  ///< how long a cycle waits for the client's command
  /// A reflex after this many seconds [s] (0: none), naming this error; lose commands or drop
  /// states then. For by-hand checks of a client's error handling.
  double reflex_at_s = 0.0;
  std::string reflex = "joint_reflex";
  double lose_at_s = 0.0;
  int lose_count = 25;
};

CLI::App* addFrankaEmulatorCommand(CLI::App& app, FrankaEmulatorCommandOptions& options);
/// Serves until stopped; a status line every second on `out`. 0, or 2 when it cannot start.
int frankaEmulatorCommand(const FrankaEmulatorCommandOptions& options, std::ostream& out,
                          std::ostream& err);

}  // namespace comply::app
