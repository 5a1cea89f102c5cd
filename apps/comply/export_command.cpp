#include "export_command.hpp"

#include <CLI/CLI.hpp>
#include <ostream>
#include <stdexcept>

#include "comply/export/lerobot_dataset.hpp"

namespace comply::app {

CLI::App* addExportCommand(CLI::App& app, ExportOptions& options) {
  CLI::App* command =
      app.add_subcommand("export",
                         "recordings (MCAP) as training data: a LeRobot v3.0 dataset, an episode "
                         "per recording (per reset of a Python Sim), a video per recorded camera "
                         "(through ffmpeg)");
  command->add_option("--lerobot", options.lerobot, "the dataset's folder (made if missing)")
      ->required();
  command->add_option("recordings", options.recordings, "the .mcap files, in episode order")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--fps", options.fps, "frames per second, sampled at exactly i / fps")
      ->capture_default_str()
      ->check(CLI::Range(1e-3, 1e4));
  command->add_option("--task", options.task, "the task every episode is given")
      ->capture_default_str();
  command->add_option("--robot-type", options.robot_type, "info.json's robot_type (default: null)");
  return command;
}

int exportCommand(const ExportOptions& options, std::ostream& out, std::ostream& err) {
  std::vector<std::filesystem::path> recordings(options.recordings.begin(),
                                                options.recordings.end());
  try {
    const exporter::LeRobotSummary summary = exporter::writeLeRobotDataset(
        options.lerobot, recordings, {options.fps, options.task, options.robot_type});
    out << "comply export: " << summary.episodes << " episode(s), " << summary.frames
        << " frames at " << options.fps << " fps into " << options.lerobot << "\n";
    for (const std::filesystem::path& file : summary.files) {
      out << "  wrote " << file.string() << "\n";
    }
    return 0;
  } catch (const std::exception& error) {
    err << "comply export: " << error.what() << "\n";
    return 2;
  }
}

}  // namespace comply::app
