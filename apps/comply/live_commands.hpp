#pragma once
// Registers `comply run`, `comply send` and `comply echo` on the command line.

#include <CLI/CLI.hpp>
#include <functional>
#include <iosfwd>
#include <memory>

namespace comply::app {

struct LiveCommands {
  std::function<bool()> parsed;
  std::function<int(std::ostream& out, std::ostream& err)> run;
};

LiveCommands addLiveCommands(CLI::App& app);

}  // namespace comply::app
