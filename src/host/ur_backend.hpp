#pragma once
// `comply run --hardware ur`: a UR e-series arm over RTDE (ur/ur_arm.hpp), set up from
// --hardware-option key=value pairs.

#include "comply/host/hardware_backends.hpp"

namespace comply::host {

HardwareBackend urArm(const pipeline::WrapperConfig& config,
                      const hardware::BackendContext& context);

}  // namespace comply::host
