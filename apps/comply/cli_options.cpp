// The options of each `comply` subcommand, declared next to each other so that `main` stays a
// dispatcher. Defaults live in the option structs (the *_command.hpp headers).

#include "cli_options.hpp"

#include <CLI/CLI.hpp>

#include "comply/core/number_text.hpp"

namespace comply::app {

CLI::Validator finiteIn(double low, double high) {
  const std::string range = "a finite number in [" + CLI::detail::to_string(low) + ", " +
                            CLI::detail::to_string(high) + "]";
  return {[low, high, range](const std::string& text) -> std::string {
            const std::optional<double> value = finiteNumber(text);
            return value && *value >= low && *value <= high ? "" : "must be " + range;
          },
          "FINITE in [" + CLI::detail::to_string(low) + ", " + CLI::detail::to_string(high) + "]"};
}

CLI::App* addBenchCommand(CLI::App& app, BenchOptions& options) {
  CLI::App* command =
      app.add_subcommand("bench", "time the plugin step and the full wrapper cycle");
  command
      ->add_option("--robot", options.robot,
                   "robot name or folder, a comma-separated list, or 'all' (the four robots and "
                   "the synthetic 12-DOF chain 'chain12')")
      ->capture_default_str();
  command->add_option("--iterations", options.iterations, "timed cycles per wrapper")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--warmup", options.warmup, "untimed cycles first")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command->add_option("--cpu", options.cpu, "pin to this CPU (-1: do not pin)")
      ->capture_default_str();
  command->add_flag("--json", options.json, "print one JSON object instead of the table");
  command
      ->add_option("--processes", options.processes,
                   "measuring processes per robot, each with another stack offset (median)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command
      ->add_option("--paced", options.paced_hz,
                   "also time the full cycle paced at this rate [Hz], sleeping between cycles as "
                   "a robot runs it (row paced_cycle), spinning (paced_spin) and woken 50 us "
                   "early to warm the caches (paced_warm); at most 3 s each per wrapper; 0: not")
      ->check(CLI::NonNegativeNumber);
  // Internal: one measuring process of the above, JSON rows on stdout.
  command->add_flag("--worker", options.worker)->group("");
  return command;
}

CLI::App* addValidateCommand(CLI::App& app, ValidateOptions& options) {
  CLI::App* command = app.add_subcommand(
      "validate", "feed synthetic samples through model + plugin (+ wrapper) on the host");
  command->add_option("--robot", options.robot, "robot name or folder");
  command->add_option("--plugin", options.plugin, "plugin name or .so path");
  command->add_option("--config", options.config_file,
                      "controller YAML (instead of the defaults for robot + plugin)");
  command->add_option("--inputs", options.inputs, "samples: [{q, dq, command}, ...]")->required();
  command->add_option("--expected", options.expected,
                      "expected outputs; report max error per output");
  command->add_option("--out", options.out, "write the outputs here (default stdout)");
  command
      ->add_option("--tolerance", options.tolerance,
                   "max absolute error per output with --expected")
      ->capture_default_str()
      ->check(finiteIn(0.0, 1e300));
  command->add_option("--period", options.period_s, "cycle period of --wrapper [s]")
      ->capture_default_str()
      ->check(finiteIn(1e-6, 1.0));
  command->add_flag("--wrapper", options.wrapper,
                    "also run the samples as consecutive cycles of the full wrapper");
  return command;
}

CLI::App* addSimCommand(CLI::App& app, SimOptions& options) {
  CLI::App* command =
      app.add_subcommand("sim", "run a controller on a simulated arm (MuJoCo), headless");
  command->add_option("--robot", options.robot, "robot name or folder (overrides the config's)");
  command->add_option("--config", options.config_file, "controller YAML");
  command->add_option("--plugin", options.plugin,
                      "without --config: plugin name (default cartesian_impedance)");
  command->add_option("--task", options.task_file, "task file: waypoints streamed over time")
      ->required();
  // The log is kept in memory for the plot (about 0.65 MB per simulated second).
  command
      ->add_option("--duration", options.duration_s,
                   "simulated seconds (default: the task's; at most 600)")
      ->check(finiteIn(1e-3, host::kMaxSimDurationS));
  command->add_option("--out", options.out_dir,
                      "output folder, made if missing (its parent must exist; default "
                      "out/sim-<robot>)");
  command->add_option("--record", options.record_path,
                      "also record every cycle, command and outcome to this MCAP file (its "
                      "folder must exist)");
  command
      ->add_option("--snapshot-every", options.snapshot_every_ms,
                   "also a PNG every N ms of simulated time (default: the task's)")
      ->check(finiteIn(0.0, 1e6));
  command->add_option("--foxglove", options.foxglove,
                      "serve a Foxglove live view on [ADDRESS:]PORT (ADDRESS default 127.0.0.1; "
                      "real time while a viewer is connected; docs/live-view.md)");
  command
      ->add_option("--foxglove-wait", options.foxglove_wait_s,
                   "with --foxglove: wait up to this long [s] for the first viewer")
      ->check(finiteIn(0.0, 3600.0));
  command->add_flag("--realtime", options.realtime, "pace the simulation to the wall clock");
  command->add_flag("--view", options.view, "open an interactive window (needs a display)");
  command->add_flag("--no-plot{false}", options.plot, "skip the matplotlib plot");
  return command;
}

CLI::App* addInspectCommand(CLI::App& app, InspectOptions& options) {
  CLI::App* command = app.add_subcommand(
      "inspect", "what a recording (MCAP) holds: channels, counts, rates, time span, drops");
  command->add_option("file", options.file, "the .mcap file")->required();
  command->add_flag("--json", options.json, "one JSON object instead of the table");
  return command;
}

CLI::App* addSchemaCommand(CLI::App& app, SchemaOptions& options) {
  CLI::App* command = app.add_subcommand(
      "schema", "print the command schema (docs/command-options.md, msg/*.msg are its output)");
  command->add_option("--format", options.format, "markdown, json, msg (ROS 2) or idl (DDS)")
      ->capture_default_str()
      ->check(CLI::IsMember({"markdown", "json", "msg", "idl"}));
  command->add_option("--kind", options.kind, "cartesian or joint (default: both)")
      ->check(CLI::IsMember({"cartesian", "joint"}));
  command
      ->add_option("--message", options.message,
                   "a host message instead of a command (--format msg or idl)")
      ->check(CLI::IsMember(
          {"ControllerState", "CommandOutcome", "ChunkTiming", "Diagnostics", "CommittedRequest"}));
  return command;
}

CLI::App* addCodegenCommand(CLI::App& app, CodegenOptions& options) {
  CLI::App* command = app.add_subcommand("codegen", "generate files for other tools");
  command->require_subcommand(1);
  CLI::App* simulink = command->add_subcommand(
      "simulink", "Simulink buses, template model and Embedded Coder adapter from the plugin ABI");
  simulink
      ->add_option("--out", options.out, "output folder, made if missing (its parent must exist)")
      ->capture_default_str();
  return simulink;
}

CLI::App* addPluginCommand(CLI::App& app, PluginNewOptions& options) {
  CLI::App* command = app.add_subcommand("plugin", "work with control-law plugins");
  command->require_subcommand(1);
  CLI::App* create = command->add_subcommand(
      "new", "write an out-of-tree plugin project (law, CMake, test, samples, sim YAML)");
  create->add_option("NAME", options.name, "plugin name, a C identifier")->required();
  create->add_option("--kind", options.kind, "command kind of the law, or hardware (a backend)")
      ->required()
      ->check(CLI::IsMember({"joint", "cartesian", "hardware"}));
  // Required for a law; pluginNewCommand says so, since a hardware backend takes none.
  create->add_option("--lang", options.language, "cpp (the C++ SDK) or c (abi.h alone)")
      ->check(CLI::IsMember({"cpp", "c"}));
  create->add_option("--out", options.out,
                     "project folder, new (its parent must exist) or empty (default ./NAME)");
  return create;
}

}  // namespace comply::app
