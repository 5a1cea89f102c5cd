#pragma once
// The value types of Universal Robots' Real-Time Data Exchange (RTDE), as its recipes name them,
// and a value of any of them. On the wire every value is big-endian (rtde_packages.hpp).

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <variant>

#include "comply/core/enum_names.hpp"

namespace comply::ur {

enum class RtdeType : std::uint8_t {
  kBool = 0,  ///< one byte, 0 or 1
  kUint8 = 1,
  kUint32 = 2,
  kUint64 = 3,
  kInt32 = 4,
  kDouble = 5,
  kVector3d = 6,  ///< three doubles
  kVector6d = 7,  ///< six doubles (joints, a pose, a wrench)
  kVector6Int32 = 8,
  kVector6Uint32 = 9,
};

/// The names a recipe's reply gives its types.
inline constexpr EnumNames<RtdeType, 10> kRtdeTypeNames{
    {{RtdeType::kBool, "BOOL"},
     {RtdeType::kUint8, "UINT8"},
     {RtdeType::kUint32, "UINT32"},
     {RtdeType::kUint64, "UINT64"},
     {RtdeType::kInt32, "INT32"},
     {RtdeType::kDouble, "DOUBLE"},
     {RtdeType::kVector3d, "VECTOR3D"},
     {RtdeType::kVector6d, "VECTOR6D"},
     {RtdeType::kVector6Int32, "VECTOR6INT32"},
     {RtdeType::kVector6Uint32, "VECTOR6UINT32"}}};

/// A setup reply's type for a variable the controller does not have, and for an input register
/// another client already writes.
inline constexpr std::string_view kNotFound = "NOT_FOUND";
inline constexpr std::string_view kInUse = "IN_USE";

/// Bytes a value of `type` takes on the wire.
std::size_t byteSize(RtdeType type) noexcept;

using RtdeValue = std::variant<bool, std::uint8_t, std::uint32_t, std::uint64_t, std::int32_t,
                               double, std::array<double, 3>, std::array<double, 6>,
                               std::array<std::int32_t, 6>, std::array<std::uint32_t, 6>>;

/// The type of a value: the variant's alternatives are in RtdeType's order.
RtdeType typeOf(const RtdeValue& value) noexcept;
/// A zero value of `type`.
RtdeValue zeroOf(RtdeType type) noexcept;

}  // namespace comply::ur
