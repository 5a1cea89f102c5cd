#pragma once
// `comply export --lerobot DIR RUN.mcap...`: recordings as a LeRobot v3.0 dataset, an episode
// per recording (per reset of a Python Sim), frames at --fps (comply/export/lerobot_dataset.hpp).

#include <iosfwd>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace comply::app {

struct ExportOptions {
  std::string lerobot;                  ///< the dataset's folder
  std::vector<std::string> recordings;  ///< one episode each, in order
  double fps = 30.0;
  std::string task = "comply recording";
  std::string robot_type;
};

CLI::App* addExportCommand(CLI::App& app, ExportOptions& options);
/// Writes the dataset and says what it wrote; 0, or 2 for input it cannot export (the reason on
/// `err`).
int exportCommand(const ExportOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
