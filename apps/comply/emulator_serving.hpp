#pragma once
// What `comply ur-emulator` and `comply franka-emulator` share: the options every emulator takes
// besides its robot's own, and the loop that serves until Ctrl-C or --duration.

#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "comply/sim/scene_xml.hpp"

namespace CLI {
class App;
}

namespace comply::app {

struct EmulatorCommonOptions {
  std::string address = "127.0.0.1";
  std::vector<std::string> objects;  ///< MuJoCo fragments added to the world (a table)
  std::string tool;                  ///< a fragment on the TCP
  double duration_s = 0.0;           ///< 0: until Ctrl-C
  int priority = 0;                  ///< SCHED_FIFO of its real-time threads (0: normal)

  /// The scene the emulated robot stands in.
  [[nodiscard]] sim::SceneOptions scene() const;
};

/// --address, --object, --tool, --duration and --priority (`priority_help` says which threads).
void addEmulatorCommonOptions(CLI::App& command, EmulatorCommonOptions& options,
                              const std::string& priority_help);

/// Until `stop` (stopOnSignals(), taken before the emulator starts) or `duration_s` (0: none):
/// `tick(elapsed_s)` every `period`, `status()` every second and once at the end.
void serveUntilStopped(const std::atomic<bool>& stop, double duration_s,
                       std::chrono::milliseconds period,
                       const std::function<void(double elapsed_s)>& tick,
                       const std::function<void()>& status);

}  // namespace comply::app
