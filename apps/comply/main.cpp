// The `comply` command line.
//
//   comply bench    --robot fr3 --iterations 10000 [--json]
//   comply validate --robot fr3 --plugin cartesian_impedance --inputs samples.json [...]
//
// Exit codes: 0 success, 1 a check failed (validate above tolerance), 2 bad input or setup.

#include <CLI/CLI.hpp>
#include <iostream>

#include "bench_command.hpp"
#include "comply/model/robot_description.hpp"
#include "validate_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"comply: compliant control of torque-controlled arms"};
  app.require_subcommand(1);

  comply::app::BenchOptions bench;
  CLI::App* bench_command =
      app.add_subcommand("bench", "time the plugin step and the full wrapper cycle");
  bench_command->add_option("--robot", bench.robot, "robot name under robots/ or a robot folder")
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

  CLI11_PARSE(app, argc, argv);
  try {
    if (bench_command->parsed()) {
      return comply::app::benchCommand(bench);
    }
    return comply::app::validateCommand(validate, std::cout, std::cerr);
  } catch (const std::exception& error) {
    std::cerr << "comply: error: " << error.what() << "\n";
    return 2;
  }
}
