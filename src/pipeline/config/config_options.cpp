// The option table (config_options.hpp) built from the tables of option_table.hpp: one Option per
// row, reading into the member the row declares.

#include "config_options.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

namespace comply::pipeline::options {
namespace {

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

/// Adds the rows of one table, whose members live in the section `of` returns.
template <typename Section>
class Rows {
 public:
  using Of = Section& (*)(WrapperConfig&);
  using OfConst = const Section& (*)(const WrapperConfig&);
  Rows(std::vector<Option>& table, Of of, OfConst of_const, bool new_block)
      : table_(table), of_(of), of_const_(of_const), first_(new_block) {}

  void number(double Section::*member, const char* key, const char* default_text,
              double default_value, Lower lower, double min, double max, const char* comment) {
    Option option(key, Kind::kNumber, comment);
    option.default_text = default_text;
    option.default_value.number = default_value;
    option.min = min;
    option.max = max;
    option.min_exclusive = lower == Lower::kAbove;
    bind(option, member, &Value::number);
    add(std::move(option));
  }

  void flag(bool Section::*member, const char* key, bool default_value, const char* comment) {
    Option option(key, Kind::kFlag, comment);
    option.default_text = default_value ? "true" : "false";
    option.default_value.flag = default_value;
    bind(option, member, &Value::flag);
    add(std::move(option));
  }

  template <typename Enum, std::size_t N>
  void choice(Enum Section::*member, const char* key, Enum default_value,
              const EnumNames<Enum, N>& names, const char* comment) {
    Option option(key, Kind::kChoice, comment);
    for (const auto& [value, name] : names) {
      option.choices.emplace_back(name);
      if (value == default_value) {
        option.default_text = name;
        option.default_value.text = name;
      }
    }
    // The tables are globals (kEnumNames beside each enum), so a pointer to one outlives the row.
    option.apply = [of = of_, member, table = &names](WrapperConfig& c, const Value& v) {
      if (const auto value = valueIn(*table, v.text)) {
        of(c).*member = *value;
      }
    };
    option.read = [of = of_const_, member, table = &names](const WrapperConfig& c) {
      Value read;
      read.text = nameIn(*table, of(c).*member, "");
      return read;
    };
    add(std::move(option));
  }

  void vector3(Eigen::Vector3d Section::*member, const char* key, double min, double max,
               const char* comment) {
    Option option(key, Kind::kVector3, comment);
    option.default_text = "[0.0, 0.0, 0.0]";
    option.default_value.numbers = {0.0, 0.0, 0.0};
    option.min = min;
    option.max = max;
    option.apply = [of = of_, member](WrapperConfig& c, const Value& v) {
      of(c).*member = Eigen::Vector3d(v.numbers[0], v.numbers[1], v.numbers[2]);
    };
    option.read = [of = of_const_, member](const WrapperConfig& c) {
      const Eigen::Vector3d& vector = of(c).*member;
      Value value;
      value.numbers = {vector.x(), vector.y(), vector.z()};
      return value;
    };
    add(std::move(option));
  }

  void perJoint(std::vector<double> Section::*member, const char* key, const char* default_text,
                double default_value, Lower lower, double min, const char* comment) {
    perJointUnset(member, key, lower, min, comment);
    table_.back().default_text = default_text;
    table_.back().default_value.numbers = {default_value};
  }

  void perJointUnset(std::vector<double> Section::*member, const char* key, Lower lower, double min,
                     const char* comment) {
    Option option(key, Kind::kPerJoint, comment);
    option.min = min;
    option.min_exclusive = lower == Lower::kAbove;
    bind(option, member, &Value::numbers);
    add(std::move(option));
  }

 private:
  /// apply and read for a member kept as it is in one slot of Value.
  template <typename T>
  void bind(Option& option, T Section::*member, T Value::*slot) {
    option.apply = [of = of_, member, slot](WrapperConfig& c, const Value& v) {
      of(c).*member = v.*slot;
    };
    option.read = [of = of_const_, member, slot](const WrapperConfig& c) {
      Value value;
      value.*slot = of(c).*member;
      return value;
    };
  }

  void add(Option option) {
    option.blank_line_before = first_;
    first_ = false;
    table_.push_back(std::move(option));
  }

  std::vector<Option>& table_;
  Of of_;
  OfConst of_const_;
  bool first_;
};

// One expansion per row kind, into calls on `rows`.
#define COMPLY_NUMBER_ROW(member, key, default_value, lower, min, max, comment)             \
  rows.number(&Section::member, key, #default_value, default_value, Lower::lower, min, max, \
              comment);
#define COMPLY_FLAG_ROW(member, key, default_value, comment) \
  rows.flag(&Section::member, key, default_value, comment);
#define COMPLY_CHOICE_ROW(member, key, Enum, default_value, comment) \
  rows.choice(&Section::member, key, Enum::default_value, k##Enum##Names, comment);
#define COMPLY_VECTOR3_ROW(member, key, min, max, comment) \
  rows.vector3(&Section::member, key, min, max, comment);
#define COMPLY_PER_JOINT_ROW(member, key, default_value, lower, min, comment) \
  rows.perJoint(&Section::member, key, #default_value, default_value, Lower::lower, min, comment);
#define COMPLY_PER_JOINT_UNSET_ROW(member, key, lower, min, comment) \
  rows.perJointUnset(&Section::member, key, Lower::lower, min, comment);

/// Adds TABLE's rows, whose members are in WrapperConfig`path` (of type SectionType); a new block
/// of the printed file when `new_block`.
#define COMPLY_ADD_OPTIONS(TABLE, SectionType, path, new_block)                      \
  {                                                                                  \
    using Section = SectionType;                                                     \
    Rows<Section> rows(                                                              \
        table, [](WrapperConfig& c) -> Section& { return c path; },                  \
        [](const WrapperConfig& c) -> const Section& { return c path; }, new_block); \
    TABLE(COMPLY_NUMBER_ROW, COMPLY_FLAG_ROW, COMPLY_CHOICE_ROW, COMPLY_VECTOR3_ROW, \
          COMPLY_PER_JOINT_ROW, COMPLY_PER_JOINT_UNSET_ROW)                          \
  }

// The tables in the order the YAML file prints them; the order is part of the file.
std::vector<Option> makeTable() {
  std::vector<Option> table;
  COMPLY_ADD_OPTIONS(COMPLY_COMMAND_OPTIONS, WrapperConfig, , true)
  COMPLY_ADD_OPTIONS(COMPLY_VALIDATION_OPTIONS, ValidationConfig, .validation, false)
  COMPLY_ADD_OPTIONS(COMPLY_COMPENSATION_OPTIONS, WrapperConfig, , true)
  COMPLY_ADD_OPTIONS(COMPLY_PAYLOAD_OPTIONS, PayloadConfig, .payload, false)
  COMPLY_ADD_OPTIONS(COMPLY_FRICTION_OPTIONS, FrictionConfig, .friction, false)
  COMPLY_ADD_OPTIONS(COMPLY_SOFT_LIMIT_OPTIONS, SoftLimitConfig, .soft_limits, true)
  COMPLY_ADD_OPTIONS(COMPLY_SHAPING_OPTIONS, WrapperConfig, , true)
  COMPLY_ADD_OPTIONS(COMPLY_GAIN_RAMP_OPTIONS, GainRampConfig, .gain_ramps, true)
  COMPLY_ADD_OPTIONS(COMPLY_PASSIVITY_OPTIONS, PassivityConfig, .passivity, true)
  COMPLY_ADD_OPTIONS(COMPLY_STABILITY_GUARD_OPTIONS, StabilityGuardConfig, .stability_guard, true)
  COMPLY_ADD_OPTIONS(COMPLY_GOVERNOR_OPTIONS, GovernorConfig, .governor, true)
  COMPLY_ADD_OPTIONS(COMPLY_WALL_OPTIONS, WallConfig, .walls, true)
  COMPLY_ADD_OPTIONS(COMPLY_REFLEX_OPTIONS, ReflexConfig, .reflex, true)
  COMPLY_ADD_OPTIONS(COMPLY_CONTACT_SPEED_OPTIONS, ContactSpeedConfig, .contact_speed, true)
  COMPLY_ADD_OPTIONS(COMPLY_OBSERVER_OPTIONS, ObserverConfig, .observer, true)
  COMPLY_ADD_OPTIONS(COMPLY_WRENCH_SENSOR_OPTIONS, WrenchSensorConfig, .wrench_sensor, true)
  COMPLY_ADD_OPTIONS(COMPLY_FORCE_CONTROL_OPTIONS, ForceControlConfig, .force_control, true)
  COMPLY_ADD_OPTIONS(COMPLY_OUTPUT_OPTIONS, OutputConfig, .output, true)
  COMPLY_ADD_OPTIONS(COMPLY_ADMITTANCE_OPTIONS, AdmittanceConfig, .output.admittance, false)
  return table;
}

}  // namespace

std::vector<std::string> keyPath(const std::string& key) {
  std::vector<std::string> path;
  std::stringstream parts(key);
  for (std::string part; std::getline(parts, part, '.');) {
    path.push_back(part);
  }
  return path;
}

std::string constraintText(const Option& option) {
  std::ostringstream text;
  if (option.kind == Kind::kFlag) {
    text << "must be true or false";
  } else if (option.kind == Kind::kChoice) {
    text << "must be ";
    for (std::size_t i = 0; i < option.choices.size(); ++i) {
      text << (i == 0 ? "" : i + 1 == option.choices.size() ? " or " : ", ") << option.choices[i];
    }
  } else if (option.min < -1e300 && option.max >= 1e300) {
    text << "must be a finite number";  // any sign: only NaN and infinities are out of range
  } else if (option.max < 1e300) {
    text << "must be in " << (option.min_exclusive ? "(" : "[") << option.min << ", " << option.max
         << "]";
  } else {
    text << "must be " << (option.min_exclusive ? "> " : ">= ") << option.min;
  }
  return text.str();
}

std::span<const Option> table() {
  static const std::vector<Option> kTable = makeTable();
  return kTable;
}

}  // namespace comply::pipeline::options
