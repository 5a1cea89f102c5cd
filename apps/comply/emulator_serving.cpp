// What the emulator commands share (emulator_serving.hpp).

#include "emulator_serving.hpp"

#include <CLI/CLI.hpp>
#include <thread>

namespace comply::app {

sim::SceneOptions EmulatorCommonOptions::scene() const {
  sim::SceneOptions scene;
  for (const std::string& object : objects) {
    scene.objects.emplace_back(object);
  }
  scene.tool = tool;
  return scene;
}

void addEmulatorCommonOptions(CLI::App& command, EmulatorCommonOptions& options,
                              const std::string& priority_help) {
  command.add_option("--address", options.address, "IPv4 address to listen on")
      ->capture_default_str();
  command.add_option("--object", options.objects, "MuJoCo fragment added to the world")
      ->check(CLI::ExistingFile);
  command.add_option("--tool", options.tool, "MuJoCo fragment on the TCP")
      ->check(CLI::ExistingFile);
  command.add_option("--duration", options.duration_s, "[s] then stop (0: until Ctrl-C)");
  command
      .add_option("--priority", options.priority,
                  "SCHED_FIFO priority of " + priority_help +
                      " (0: normal; refused quietly where not permitted)")
      ->check(CLI::Range(0, 99));
}

void serveUntilStopped(const std::atomic<bool>& stop, double duration_s,
                       std::chrono::milliseconds period,
                       const std::function<void(double elapsed_s)>& tick,
                       const std::function<void()>& status) {
  const auto start = std::chrono::steady_clock::now();
  auto next_status = start + std::chrono::seconds(1);
  while (!stop.load()) {
    std::this_thread::sleep_for(period);
    const auto now = std::chrono::steady_clock::now();
    const double elapsed_s = std::chrono::duration<double>(now - start).count();
    tick(elapsed_s);
    if (now >= next_status) {
      status();
      next_status += std::chrono::seconds(1);
    }
    if (duration_s > 0.0 && elapsed_s >= duration_s) {
      break;
    }
  }
  status();
}

}  // namespace comply::app
