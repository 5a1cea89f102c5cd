#pragma once
// The wrapper's options, declared once: key, kind, default, allowed range and the comment that
// documents it. The parser reads every option through this table (an absent key takes the
// default written here) and `comply config --defaults` prints it, so the documented file and the
// parser cannot disagree.

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

struct Option {
  Option(const char* key_in, Kind kind_in, const char* default_in, const char* comment_in,
         double min_in = 0.0, double max_in = 1e300, bool min_exclusive_in = false)
      : key(key_in),
        kind(kind_in),
        default_text(default_in),
        comment(comment_in),
        min(min_in),
        max(max_in),
        min_exclusive(min_exclusive_in) {}

  const char* key;  ///< dotted path under ros__parameters ("soft_limits.stiffness")
  Kind kind;
  const char* default_text;  ///< YAML of the default; nullptr: none (the comment says what then)
  const char* comment;       ///< unit and meaning, as printed in the documented file
  double min = 0.0;          ///< numbers and per-joint entries: allowed range
  double max = 1e300;
  bool min_exclusive = false;
  const char* choices = "";  ///< kChoice: alternatives separated by '|'
  std::function<void(WrapperConfig&, const Value&)> apply;
  bool blank_line_before = false;  ///< layout of the printed file
};

/// Every option, in the order of the documented file.
std::span<const Option> table();

/// Keys that are read outside the table (names, plugin parameters, the initial block).
inline constexpr const char* kSpecialKeys[] = {
    "plugin", "plugin_parameters", "robot", "joints", "base_frame", "tip_frame", "initial"};

}  // namespace comply::pipeline::options
