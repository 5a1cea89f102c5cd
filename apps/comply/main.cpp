// The `comply` command line.
//
//   comply bench    --robot fr3|all|fr3,ur5e,chain12 --iterations 10000 [--processes 5] [--json]
//   comply validate --robot fr3 --plugin cartesian_impedance --inputs samples.json [...]
//   comply sim --robot fr3 --config controller.yaml --task task.yaml [--out DIR] [...]
//   comply experiment cross-platform|surface-following|connector-mating|passivity [--out DIR]
//   comply run --config controller.yaml --sim [--robot R] [--rate HZ] [--domain N] [--name NAME]
//   comply send --json '{"position": [...]}' | --file F [--rate HZ]
//   comply echo [state|diagnostics]
//   comply inspect FILE [--json]
//   comply export --lerobot DIR RUN.mcap... [--fps 30] [--task TEXT]
//   comply schema [--format markdown|json|msg|idl] [--kind cartesian|joint]
//   comply codegen simulink [--out DIR]
//   comply plugin new NAME --kind joint|cartesian --lang cpp|c [--out DIR]
//   comply plugin new NAME --kind hardware [--out DIR]
//   comply config --defaults [--robot fr3] [--plugin cartesian_impedance]
//   comply ur-emulator [--rtde-port 30004] [--object table.xml] [--duration S]
//   comply franka-emulator [--command-port 1337] [--object table.xml] [--duration S]
//
// Exit codes: 0 success, 1 a check failed (validate above tolerance, a controller fault, a
// target not reached), 2 bad input or setup.

#include <CLI/CLI.hpp>
#include <iostream>
#include <new>

#include "cli_options.hpp"
#include "config_command.hpp"
#include "emulator_commands.hpp"
#include "experiment_commands.hpp"
#include "export_command.hpp"
#include "live_commands.hpp"

int main(int argc, char** argv) {
  using namespace comply::app;
  CLI::App app{"comply: compliant control of torque-controlled arms"};
  app.require_subcommand(1);
  BenchOptions bench;
  ValidateOptions validate;
  SimOptions sim;
  SchemaOptions schema;
  InspectOptions inspect;
  ExportOptions export_options;
  ConfigOptions config;
  CodegenOptions codegen;
  PluginNewOptions plugin_new;
  CLI::App* bench_command = addBenchCommand(app, bench);
  CLI::App* validate_command = addValidateCommand(app, validate);
  CLI::App* sim_command = addSimCommand(app, sim);
  const comply::experiments::Commands experiments = comply::experiments::addCommands(app);
  const LiveCommands live = addLiveCommands(app);
  CLI::App* schema_command = addSchemaCommand(app, schema);
  CLI::App* inspect_command = addInspectCommand(app, inspect);
  CLI::App* export_command = addExportCommand(app, export_options);
  CLI::App* config_command = addConfigCommand(app, config);
  CLI::App* codegen_simulink = addCodegenCommand(app, codegen);
  CLI::App* plugin_new_command = addPluginCommand(app, plugin_new);
  const EmulatorCommands emulators = addEmulatorCommands(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    // --help prints and succeeds; every malformed argument is bad input, exit 2 as documented.
    return app.exit(error) == 0 ? 0 : 2;
  }
  try {
    if (bench_command->parsed()) {
      return benchCommand(bench);
    }
    if (validate_command->parsed()) {
      return validateCommand(validate, std::cout, std::cerr);
    }
    if (sim_command->parsed()) {
      return simCommand(sim, std::cout, std::cerr);
    }
    if (live.parsed()) {
      return live.run(std::cout, std::cerr);
    }
    if (experiments.parsed()) {
      return experiments.run(std::cout, std::cerr);
    }
    if (inspect_command->parsed()) {
      return inspectCommand(inspect, std::cout, std::cerr);
    }
    if (export_command->parsed()) {
      return exportCommand(export_options, std::cout, std::cerr);
    }
    if (schema_command->parsed()) {
      return schemaCommand(schema, std::cout, std::cerr);
    }
    if (config_command->parsed()) {
      return configCommand(config, std::cout, std::cerr);
    }
    if (codegen_simulink->parsed()) {
      return codegenSimulinkCommand(codegen, std::cout, std::cerr);
    }
    if (plugin_new_command->parsed()) {
      return pluginNewCommand(plugin_new, std::cout, std::cerr);
    }
    if (emulators.parsed()) {
      return emulators.run(std::cout, std::cerr);
    }
    return 2;
  } catch (const std::bad_alloc&) {
    std::cerr << "comply: error: out of memory (is an input far larger than it should be?)\n";
    return 2;
  } catch (const std::exception& error) {
    std::cerr << "comply: error: " << error.what() << "\n";
    return 2;
  }
}
