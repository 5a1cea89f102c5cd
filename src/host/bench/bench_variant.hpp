#pragma once
// The set-up of a benchmarked wrapper (cycle_bench.cpp): what it has on besides its law, in its
// configuration and in the commands it holds before the timed cycles. Private to the host.

#include <string>

#include "comply/pipeline/wrapper.hpp"

namespace comply::host::bench {

/// What a benchmarked wrapper has on besides its law.
struct Variant {
  DampingMode damping_mode = DampingMode::kRatio;
  bool gain_stage = false;     ///< ramps and energy tank
  bool recorded = false;       ///< the cycle pushed into a recording's lane
  bool observer = false;       ///< the momentum observer
  bool chunked = false;        ///< a timed chunk plays through every cycle
  bool force = false;          ///< a force axis and contact-force limits (with the observer)
  bool walls = false;          ///< four walls and a box around the workspace (virtual_walls.hpp)
  bool reflex = false;         ///< the contact reflex armed on the observer's wrench
  bool contact_speed = false;  ///< the contact-speed stage (contact_speed.hpp), hands' limits
  OutputMode output = OutputMode::kTorque;  ///< what the drives take (output.mode)
};

/// The configuration of `plugin` on `robot` (controllerConfig) with `variant` on.
pipeline::WrapperConfig variantConfig(const std::string& robot, const std::string& plugin,
                                      const Variant& variant);

/// The commands of `variant` into the activated `wrapper`: the force command, the chunk that
/// lasts `run_s`. Throws when the wrapper refuses one (its message names `wrapper_name`).
void submitVariantCommands(pipeline::Wrapper<CartesianCommand>& wrapper, const Variant& variant,
                           const std::string& wrapper_name, double run_s);

}  // namespace comply::host::bench
