#pragma once
// The `comply experiment` subcommands, for the command line to register:
//
//   const comply::experiments::Commands experiments = comply::experiments::addCommands(app);
//   CLI11_PARSE(app, argc, argv);
//   if (experiments.parsed()) return experiments.run(std::cout, std::cerr);
//
// Running is left to the caller, after parsing, so that an experiment's exception reaches the
// command line's own handler (exit code 2) like every other subcommand's.

#include <iosfwd>
#include <memory>

namespace CLI {
class App;
}  // namespace CLI

namespace comply::experiments {

class Commands {
 public:
  struct State;
  explicit Commands(std::unique_ptr<State> state);
  Commands(Commands&&) noexcept;
  Commands& operator=(Commands&&) noexcept;
  ~Commands();

  /// True when the command line chose an experiment.
  [[nodiscard]] bool parsed() const;
  /// Runs the chosen experiment and returns its exit code: 0 success, 1 a check failed
  /// (cross-platform: a robot missed the target). Throws on bad input or setup.
  [[nodiscard]] int run(std::ostream& out, std::ostream& err) const;

 private:
  std::unique_ptr<State> state_;
};

/// Adds `experiment cross-platform|surface-following|connector-mating|passivity|chunks` with their
/// options to `app`; the options are bound to storage the returned handle owns, so keep it until
/// run().
Commands addCommands(CLI::App& app);

}  // namespace comply::experiments
