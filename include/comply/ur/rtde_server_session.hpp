#pragma once
// A UR controller's side of one RTDE connection, without its socket: the packages a client sends
// in, the controller's answers out. It agrees on protocol version 2, sets up the output recipe
// (variables the controller has, at a frequency it can serve) and input recipes (registers no
// other recipe writes), starts and pauses, and keeps what the client last wrote to its inputs.
// comply's UR controller emulator runs one per client; the rules are the RTDE description's:
// recipes are set up while paused, a recipe naming a variable the controller lacks cannot start,
// data packages come only while started.

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "comply/ur/rtde_packages.hpp"
#include "comply/ur/rtde_variables.hpp"

namespace comply::ur {

struct OutputRecipe {
  std::uint8_t id = 0;
  double frequency_hz = 0.0;
  std::vector<std::string> names;
  std::vector<RtdeType> types;
};

class RtdeServerSession {
 public:
  /// `max_frequency_hz`: the fastest output the controller serves (e-series 500, CB3 125).
  explicit RtdeServerSession(ControllerVersion version, double max_frequency_hz = 500.0);

  /// The answers to `package`, in order (none to a data package). A package the session cannot
  /// take is answered with a text message saying why (level error), and changes nothing.
  std::vector<std::vector<std::uint8_t>> handle(const Package& package);

  /// Inputs other clients write: a set-up asking for one is answered IN_USE, as a controller
  /// lets one client at a time write an input. Set before handle().
  void setInputsTakenElsewhere(std::set<std::string> names) { taken_elsewhere_ = std::move(names); }
  /// Every input this session's recipes write.
  [[nodiscard]] std::set<std::string> inputNames() const;

  [[nodiscard]] bool started() const noexcept { return started_; }
  [[nodiscard]] std::uint16_t protocolVersion() const noexcept { return protocol_version_; }
  /// The output recipe once one was set up with every variable found.
  [[nodiscard]] const std::optional<OutputRecipe>& output() const noexcept { return output_; }
  /// What the client last wrote to each input variable, by name (none before it writes).
  [[nodiscard]] const std::map<std::string, RtdeValue>& inputs() const noexcept { return inputs_; }
  /// The output recipe's data package of `values` (in the recipe's order and types). Throws
  /// RtdeError without an output recipe or when the values do not match it.
  [[nodiscard]] std::vector<std::uint8_t> outputPackage(std::span<const RtdeValue> values) const;

 private:
  std::vector<std::uint8_t> setupOutputs(const Package& package);
  std::vector<std::uint8_t> setupInputs(const Package& package);
  void takeInputs(const Package& package);
  static std::vector<std::uint8_t> error(const std::string& message);

  ControllerVersion version_;
  double max_frequency_hz_;
  std::uint16_t protocol_version_ = 0;  // 0: not agreed yet
  bool started_ = false;
  std::optional<OutputRecipe> output_;
  std::uint8_t next_recipe_id_ = 1;
  struct InputRecipe {
    std::vector<std::string> names;
    std::vector<RtdeType> types;
  };
  std::map<std::uint8_t, InputRecipe> input_recipes_;
  std::set<std::string> taken_elsewhere_;
  std::map<std::string, RtdeValue> inputs_;
};

}  // namespace comply::ur
