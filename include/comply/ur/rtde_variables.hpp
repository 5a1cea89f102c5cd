#pragma once
// The variables a UR e-series controller serves over RTDE (outputs: what a client reads) and
// takes (inputs: what a client writes), by name and type, as the RTDE description lists them:
// the ones comply's UR backend and emulator use, and the general-purpose registers by pattern
// (input_double_register_0 to _47, input_bit_register_64 to _127, ...).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "comply/ur/rtde_packages.hpp"
#include "comply/ur/rtde_types.hpp"

namespace comply::ur {

enum class Direction : std::uint8_t {
  kOutput,  ///< the controller's to send (SETUP_OUTPUTS)
  kInput,   ///< a client's to write (SETUP_INPUTS)
};

struct RtdeVariable {
  std::string name;
  RtdeType type = RtdeType::kDouble;
  Direction direction = Direction::kOutput;
};

/// The variable `name`; none when the controller has none by that name.
std::optional<RtdeVariable> findVariable(std::string_view name);

/// What a controller answers a recipe's setup for `names` in `direction`: each variable's type,
/// or kNotFound for a name it does not have in that direction.
SetupReply answerSetup(std::uint8_t recipe_id, const std::vector<std::string>& names,
                       Direction direction);

}  // namespace comply::ur
