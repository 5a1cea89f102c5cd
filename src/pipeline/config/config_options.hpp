#pragma once
// The wrapper's options as the parser reads them: one Option per row of the tables in
// comply/pipeline/option_table.hpp (key, kind, default, allowed range and the comment that
// documents it). The parser reads every option through this table (an absent key takes the
// row's default, the same the struct member starts with), and `comply config --defaults` prints
// it, so the documented file, the structs and the parser cannot disagree.

#include <yaml-cpp/yaml.h>

#include <functional>
#include <span>
#include <string>
#include <vector>

#include "comply/pipeline/config.hpp"

namespace comply::pipeline::options {

enum class Kind { kNumber, kFlag, kChoice, kVector3, kPerJoint };

/// A value as read: the member that matches the option's kind is set.
struct Value {
  double number = 0.0;
  bool flag = false;
  std::string text;
  std::vector<double> numbers;
};

/// Whether an option's lower bound is allowed (kAtLeast) or not (kAbove).
enum class Lower { kAtLeast, kAbove };

struct Option {
  Option(const char* key_in, Kind kind_in, const char* comment_in)
      : key(key_in), kind(kind_in), comment(comment_in) {}

  const char* key;  ///< dotted path under ros__parameters ("soft_limits.stiffness")
  Kind kind;
  const char* comment;       ///< unit and meaning, as printed in the documented file
  std::string default_text;  ///< YAML of the default as written in the table; empty: none
  Value default_value;       ///< the same, read
  double min = -1e300;       ///< numbers and per-joint entries: allowed range
  double max = 1e300;
  bool min_exclusive = false;
  std::vector<std::string> choices;                         ///< kChoice: the alternatives
  std::function<void(WrapperConfig&, const Value&)> apply;  ///< sets the member
  std::function<Value(const WrapperConfig&)> read;          ///< the member's value
  bool blank_line_before = false;  ///< layout of the printed file: a new block starts here

  [[nodiscard]] bool hasDefault() const { return !default_text.empty(); }
};

/// Every option, in the order of the documented file.
std::span<const Option> table();

/// The parts of a dotted key ("soft_limits.stiffness" -> soft_limits, stiffness); an empty part
/// stays, so that a caller can refuse it.
std::vector<std::string> keyPath(const std::string& key);

/// What a value of `option` must be, as the parser says it ("must be > 0", "must be hold or
/// reanchor").
std::string constraintText(const Option& option);

/// The controller's parameters (the mapping under ros__parameters) read into a configuration:
/// the names, every option of the table, the plugin parameters and the initial block. Throws
/// InputError naming `source` and the key.
WrapperConfig parseParameters(const YAML::Node& parameters, const std::string& source,
                              const std::string& controller_name);

/// The walls: and boxes: lists into `walls` (config_walls.cpp). Throws InputError naming the
/// entry ("walls[1].normal") under `root`.
void readWalls(const YAML::Node& parameters, const std::string& source, const std::string& root,
               WallConfig& walls);

/// Keys that are read outside the table (names, plugin parameters, the initial block, the walls).
inline constexpr const char* kSpecialKeys[] = {
    "plugin",    "plugin_parameters", "robot", "joints", "base_frame",
    "tip_frame", "initial",           "walls", "boxes"};

}  // namespace comply::pipeline::options
