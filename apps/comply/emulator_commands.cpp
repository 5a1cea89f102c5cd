// The emulators' commands (emulator_commands.hpp).

#include "emulator_commands.hpp"

#include <CLI/CLI.hpp>
#include <memory>

#include "franka_emulator_command.hpp"
#include "ur_emulator_command.hpp"

namespace comply::app {

EmulatorCommands addEmulatorCommands(CLI::App& app) {
  // The options outlive this call: the parsed values are read when the command runs.
  auto ur = std::make_shared<UrEmulatorCommandOptions>();
  auto franka = std::make_shared<FrankaEmulatorCommandOptions>();
  CLI::App* ur_command = addUrEmulatorCommand(app, *ur);
  CLI::App* franka_command = addFrankaEmulatorCommand(app, *franka);
  EmulatorCommands commands;
  commands.parsed = [=] { return ur_command->parsed() || franka_command->parsed(); };
  commands.run = [=](std::ostream& out, std::ostream& err) {
    if (ur_command->parsed()) {
      return urEmulatorCommand(*ur, out, err);
    }
    return frankaEmulatorCommand(*franka, out, err);
  };
  return commands;
}

}  // namespace comply::app
