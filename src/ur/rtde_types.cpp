// RTDE value types (see rtde_types.hpp).

#include "comply/ur/rtde_types.hpp"

namespace comply::ur {

std::size_t byteSize(RtdeType type) noexcept {
  switch (type) {
    case RtdeType::kBool:
    case RtdeType::kUint8:
      return 1;
    case RtdeType::kUint32:
    case RtdeType::kInt32:
      return 4;
    case RtdeType::kUint64:
    case RtdeType::kDouble:
      return 8;
    case RtdeType::kVector3d:
      return 24;
    case RtdeType::kVector6d:
      return 48;
    case RtdeType::kVector6Int32:
    case RtdeType::kVector6Uint32:
      return 24;
  }
  return 0;
}

RtdeType typeOf(const RtdeValue& value) noexcept {
  return static_cast<RtdeType>(value.index());
}

RtdeValue zeroOf(RtdeType type) noexcept {
  switch (type) {
    case RtdeType::kBool:
      return false;
    case RtdeType::kUint8:
      return std::uint8_t{0};
    case RtdeType::kUint32:
      return std::uint32_t{0};
    case RtdeType::kUint64:
      return std::uint64_t{0};
    case RtdeType::kInt32:
      return std::int32_t{0};
    case RtdeType::kDouble:
      return 0.0;
    case RtdeType::kVector3d:
      return std::array<double, 3>{};
    case RtdeType::kVector6d:
      return std::array<double, 6>{};
    case RtdeType::kVector6Int32:
      return std::array<std::int32_t, 6>{};
    case RtdeType::kVector6Uint32:
      return std::array<std::uint32_t, 6>{};
  }
  return false;
}

}  // namespace comply::ur
