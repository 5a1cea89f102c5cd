// The `comply` command line.
//
//   comply bench    --robot fr3|all|fr3,ur5e,chain12 --iterations 10000 [--processes 5] [--json]
//   comply validate --robot fr3 --plugin cartesian_impedance --inputs samples.json [...]
//   comply sim --robot fr3 --config controller.yaml --task task.yaml [--out DIR] [...]
//   comply experiment cross-platform [--out DIR]
//   comply schema [--format markdown|json|msg] [--kind cartesian|joint]
//
// Exit codes: 0 success, 1 a check failed (validate above tolerance, a controller fault, a
// target not reached), 2 bad input or setup.

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench_command.hpp"
#include "comply/model/robot_description.hpp"
#include "experiment_commands.hpp"
#include "schema_command.hpp"
#include "sim_command.hpp"
#include "validate_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"comply: compliant control of torque-controlled arms"};
  app.require_subcommand(1);

  comply::app::BenchOptions bench;
  CLI::App* bench_command =
      app.add_subcommand("bench", "time the plugin step and the full wrapper cycle");
  bench_command
      ->add_option("--robot", bench.robot,
                   "robot name or folder, a comma-separated list, or 'all' (the four robots and "
                   "the synthetic 12-DOF chain 'chain12')")
      ->capture_default_str();
  bench_command->add_option("--iterations", bench.iterations, "timed cycles per wrapper")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  bench_command->add_option("--warmup", bench.warmup, "untimed cycles first")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  bench_command->add_option("--cpu", bench.cpu, "pin to this CPU (-1: do not pin)")
      ->capture_default_str();
  bench_command->add_flag("--json", bench.json, "print one JSON object instead of the table");
  bench_command
      ->add_option("--processes", bench.processes,
                   "measuring processes per robot, each with another stack offset (median)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  // Internal: one measuring process of the above, JSON rows on stdout.
  bench_command->add_flag("--worker", bench.worker)->group("");

  comply::app::ValidateOptions validate;
  CLI::App* validate_command = app.add_subcommand(
      "validate", "feed synthetic samples through model + plugin (+ wrapper) on the host");
  validate_command->add_option("--robot", validate.robot, "robot name or folder");
  validate_command->add_option("--plugin", validate.plugin, "plugin name or .so path");
  validate_command->add_option("--config", validate.config_file,
                               "controller YAML (instead of the defaults for robot + plugin)");
  validate_command->add_option("--inputs", validate.inputs, "samples: [{q, dq, command}, ...]")
      ->required();
  validate_command->add_option("--expected", validate.expected,
                               "expected outputs; report max error per output");
  validate_command->add_option("--out", validate.out, "write the outputs here (default stdout)");
  validate_command
      ->add_option("--tolerance", validate.tolerance,
                   "max absolute error per output with --expected")
      ->capture_default_str();
  validate_command->add_option("--period", validate.period_s, "cycle period of --wrapper [s]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  validate_command->add_flag("--wrapper", validate.wrapper,
                             "also run the samples as consecutive cycles of the full wrapper");

  comply::app::SimOptions sim;
  CLI::App* sim_command =
      app.add_subcommand("sim", "run a controller on a simulated arm (MuJoCo), headless");
  sim_command->add_option("--robot", sim.robot, "robot name or folder (overrides the config's)");
  sim_command->add_option("--config", sim.config_file, "controller YAML");
  sim_command->add_option("--plugin", sim.plugin,
                          "without --config: plugin name (default cartesian_impedance)");
  sim_command->add_option("--task", sim.task_file, "task file: waypoints streamed over time")
      ->required();
  sim_command->add_option("--duration", sim.duration_s, "simulated seconds (default: the task's)")
      ->check(CLI::PositiveNumber);
  sim_command->add_option("--out", sim.out_dir, "output folder (default out/sim-<robot>)");
  sim_command
      ->add_option("--snapshot-every", sim.snapshot_every_ms,
                   "also a PNG every N ms of simulated time (default: the task's)")
      ->check(CLI::NonNegativeNumber);
  sim_command->add_flag("--realtime", sim.realtime, "pace the simulation to the wall clock");
  sim_command->add_flag("--view", sim.view, "open an interactive window (needs a display)");
  sim_command->add_flag("--no-plot{false}", sim.plot, "skip the matplotlib plot");

  const comply::experiments::Commands experiments = comply::experiments::addCommands(app);

  comply::app::SchemaOptions schema;
  CLI::App* schema_command = app.add_subcommand(
      "schema", "print the command schema (docs/command-schema.md, msg/*.msg are its output)");
  schema_command->add_option("--format", schema.format, "markdown, json or msg (ROS 2)")
      ->capture_default_str()
      ->check(CLI::IsMember({"markdown", "json", "msg"}));
  schema_command->add_option("--kind", schema.kind, "cartesian or joint (default: both)")
      ->check(CLI::IsMember({"cartesian", "joint"}));

  CLI11_PARSE(app, argc, argv);
  try {
    if (bench_command->parsed()) {
      return comply::app::benchCommand(bench);
    }
    if (schema_command->parsed()) {
      return comply::app::schemaCommand(schema, std::cout, std::cerr);
    }
    if (sim_command->parsed()) {
      return comply::app::simCommand(sim, std::cout, std::cerr);
    }
    if (experiments.parsed()) {
      return experiments.run(std::cout, std::cerr);
    }
    return comply::app::validateCommand(validate, std::cout, std::cerr);
  } catch (const std::exception& error) {
    std::cerr << "comply: error: " << error.what() << "\n";
    return 2;
  }
}
