#pragma once
// `comply ur-emulator` and `comply franka-emulator`: a robot's controller emulated on the MuJoCo
// plant, for a backend (or the vendor's client library) without the robot.

#include <functional>
#include <iosfwd>

namespace CLI {
class App;
}

namespace comply::app {

struct EmulatorCommands {
  std::function<bool()> parsed;
  std::function<int(std::ostream& out, std::ostream& err)> run;
};

EmulatorCommands addEmulatorCommands(CLI::App& app);

}  // namespace comply::app
