// `comply run`: options and signals around the host (live_host.cpp).

#include "run_command.hpp"

#include <atomic>
#include <ostream>

#include "comply/core/output_folder.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/host/live_host.hpp"
#include "comply/host/live_view.hpp"
#include "comply/pipeline/config.hpp"
#include "comply/sim/viewer.hpp"
#include "stop_signal.hpp"

namespace comply::app {
namespace {

std::string checkOptions(const RunOptions& options) {
  if (options.config_file.empty()) {
    return "--config is required";
  }
  if (options.sim && options.hardware != "sim") {
    return "--sim and --hardware " + options.hardware + " name two different robots";
  }
  if (options.view) {
    return "--view is not supported by comply run yet; watch /" + options.name +
           "/state with `comply echo`";
  }
  if (!(options.rate_hz > 0.0) || !(options.state_rate_hz > 0.0)) {
    return "--rate and --state-rate must be positive";
  }
  if (options.network != "loopback" && options.network != "all") {
    return "--network must be loopback or all";
  }
  if (!options.record_path.empty()) {
    if (const std::string why = missingFolderOf(options.record_path); !why.empty()) {
      return "cannot record to " + options.record_path + ": " + why;
    }
  }
  if (!options.foxglove.empty()) {
    try {
      (void)host::parseViewAddress(options.foxglove);
    } catch (const std::invalid_argument& error) {
      return error.what();
    }
  }
  return {};
}

}  // namespace

int runCommand(const RunOptions& options, std::ostream& out, std::ostream& err) {
  if (const std::string problem = checkOptions(options); !problem.empty()) {
    err << "comply run: " << problem << "\n";
    return 2;
  }
  const pipeline::WrapperConfig config =
      host::simControllerConfig(options.robot, "", options.config_file);
  std::atomic<bool>& stop_requested = stopOnSignals();
  RunOptions locked = options;
  locked.lock_memory = true;
  return host::runLiveHost(locked, config, stop_requested, out, err);
}

}  // namespace comply::app
