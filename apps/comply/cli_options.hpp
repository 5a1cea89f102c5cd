#pragma once
// Registers each subcommand's options with the command line; the returned App says whether it
// was chosen.

#include "bench_command.hpp"
#include "codegen_command.hpp"
#include "inspect_command.hpp"
#include "plugin_command.hpp"
#include "schema_command.hpp"
#include "sim_command.hpp"
#include "validate_command.hpp"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace comply::app {

/// A finite number in [low, high]: CLI11's own range checks let NaN through (every comparison
/// with NaN is false) and the sim would then ignore the option silently.
CLI::Validator finiteIn(double low, double high);

CLI::App* addBenchCommand(CLI::App& app, BenchOptions& options);
CLI::App* addValidateCommand(CLI::App& app, ValidateOptions& options);
CLI::App* addSimCommand(CLI::App& app, SimOptions& options);
CLI::App* addInspectCommand(CLI::App& app, InspectOptions& options);
CLI::App* addSchemaCommand(CLI::App& app, SchemaOptions& options);
/// `comply codegen simulink`; returns the `simulink` subcommand.
CLI::App* addCodegenCommand(CLI::App& app, CodegenOptions& options);
/// `comply plugin new`; returns the `new` subcommand.
CLI::App* addPluginCommand(CLI::App& app, PluginNewOptions& options);

}  // namespace comply::app
