// The controller's RTDE variables (see rtde_variables.hpp).

#include "comply/ur/rtde_variables.hpp"

#include <array>
#include <charconv>

namespace comply::ur {
namespace {

struct Named {
  std::string_view name;
  RtdeType type;
  Direction direction;
};

constexpr Direction kOut = Direction::kOutput;
constexpr Direction kIn = Direction::kInput;

constexpr std::array kVariables{
    Named{"timestamp", RtdeType::kDouble, kOut},  // the controller's time since it started [s]
    Named{"target_q", RtdeType::kVector6d, kOut},
    Named{"target_qd", RtdeType::kVector6d, kOut},
    Named{"target_qdd", RtdeType::kVector6d, kOut},
    Named{"target_current", RtdeType::kVector6d, kOut},
    Named{"target_moment", RtdeType::kVector6d, kOut},
    Named{"actual_q", RtdeType::kVector6d, kOut},
    Named{"actual_qd", RtdeType::kVector6d, kOut},
    Named{"actual_current", RtdeType::kVector6d, kOut},
    // The joint currents as torques [N m]: PolyScope 5.23 / 10.10 and later.
    Named{"actual_current_as_torque", RtdeType::kVector6d, kOut},
    Named{"joint_control_output", RtdeType::kVector6d, kOut},
    Named{"actual_TCP_pose", RtdeType::kVector6d, kOut},
    Named{"actual_TCP_speed", RtdeType::kVector6d, kOut},
    Named{"actual_TCP_force", RtdeType::kVector6d, kOut},
    Named{"target_TCP_pose", RtdeType::kVector6d, kOut},
    Named{"target_TCP_speed", RtdeType::kVector6d, kOut},
    Named{"ft_raw_wrench", RtdeType::kVector6d, kOut},
    Named{"joint_temperatures", RtdeType::kVector6d, kOut},
    Named{"actual_execution_time", RtdeType::kDouble, kOut},
    Named{"robot_mode", RtdeType::kInt32, kOut},
    Named{"joint_mode", RtdeType::kVector6Int32, kOut},
    Named{"safety_mode", RtdeType::kInt32, kOut},
    Named{"safety_status", RtdeType::kInt32, kOut},
    Named{"robot_status_bits", RtdeType::kUint32, kOut},
    Named{"safety_status_bits", RtdeType::kUint32, kOut},
    Named{"runtime_state", RtdeType::kUint32, kOut},
    Named{"speed_scaling", RtdeType::kDouble, kOut},
    Named{"target_speed_fraction", RtdeType::kDouble, kOut},
    Named{"actual_tool_accelerometer", RtdeType::kVector3d, kOut},
    Named{"actual_digital_input_bits", RtdeType::kUint64, kOut},
    Named{"actual_digital_output_bits", RtdeType::kUint64, kOut},
    Named{"payload", RtdeType::kDouble, kOut},
    Named{"speed_slider_mask", RtdeType::kUint32, kIn},
    Named{"speed_slider_fraction", RtdeType::kDouble, kIn},
    Named{"standard_digital_output_mask", RtdeType::kUint8, kIn},
    Named{"standard_digital_output", RtdeType::kUint8, kIn},
};

/// A general-purpose register: `prefix` then a number in [first, last].
struct RegisterBank {
  std::string_view prefix;
  int first;
  int last;
  RtdeType type;
  Direction direction;
};

constexpr std::array kRegisters{
    RegisterBank{"input_bit_register_", 64, 127, RtdeType::kBool, kIn},
    RegisterBank{"input_int_register_", 0, 47, RtdeType::kInt32, kIn},
    RegisterBank{"input_double_register_", 0, 47, RtdeType::kDouble, kIn},
    RegisterBank{"output_bit_register_", 64, 127, RtdeType::kBool, kOut},
    RegisterBank{"output_int_register_", 0, 47, RtdeType::kInt32, kOut},
    RegisterBank{"output_double_register_", 0, 47, RtdeType::kDouble, kOut},
};

std::optional<RtdeVariable> findRegister(std::string_view name) {
  for (const RegisterBank& bank : kRegisters) {
    if (!name.starts_with(bank.prefix)) {
      continue;
    }
    const std::string_view digits = name.substr(bank.prefix.size());
    int number = -1;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
    // "07" is not a register's name: the controller spells them without leading zeros.
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() ||
        (digits.size() > 1 && digits.front() == '0') || number < bank.first || number > bank.last) {
      return std::nullopt;
    }
    return RtdeVariable{std::string(name), bank.type, bank.direction};
  }
  return std::nullopt;
}

}  // namespace

std::optional<RtdeVariable> findVariable(std::string_view name) {
  for (const Named& variable : kVariables) {
    if (variable.name == name) {
      return RtdeVariable{std::string(name), variable.type, variable.direction};
    }
  }
  return findRegister(name);
}

SetupReply answerSetup(std::uint8_t recipe_id, const std::vector<std::string>& names,
                       Direction direction) {
  SetupReply reply;
  reply.recipe_id = recipe_id;
  for (const std::string& name : names) {
    const std::optional<RtdeVariable> variable = findVariable(name);
    reply.types.emplace_back(variable && variable->direction == direction
                                 ? nameIn(kRtdeTypeNames, variable->type)
                                 : kNotFound);
  }
  return reply;
}

}  // namespace comply::ur
