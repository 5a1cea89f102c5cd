// RTDE's data packages and recipes (see rtde_packages.hpp).

#include <type_traits>

#include "big_endian.hpp"
#include "comply/ur/rtde_packages.hpp"

namespace comply::ur {
namespace {

template <typename Element, std::size_t N>
void putArray(wire::Writer& w, const std::array<Element, N>& values) {
  for (const Element value : values) {
    w.put(value);
  }
}

template <typename Element, std::size_t N>
std::array<Element, N> getArray(wire::Reader& r) {
  std::array<Element, N> values{};
  for (Element& value : values) {
    value = r.get<Element>();
  }
  return values;
}

RtdeValue getValue(wire::Reader& r, RtdeType type) {
  switch (type) {
    case RtdeType::kBool: {
      const auto byte = r.get<std::uint8_t>();
      if (byte > 1) {
        throw RtdeError("a data package's BOOL holds " + std::to_string(byte));
      }
      return byte == 1;
    }
    case RtdeType::kUint8:
      return r.get<std::uint8_t>();
    case RtdeType::kUint32:
      return r.get<std::uint32_t>();
    case RtdeType::kUint64:
      return r.get<std::uint64_t>();
    case RtdeType::kInt32:
      return r.get<std::int32_t>();
    case RtdeType::kDouble:
      return r.get<double>();
    case RtdeType::kVector3d:
      return getArray<double, 3>(r);
    case RtdeType::kVector6d:
      return getArray<double, 6>(r);
    case RtdeType::kVector6Int32:
      return getArray<std::int32_t, 6>(r);
    case RtdeType::kVector6Uint32:
      return getArray<std::uint32_t, 6>(r);
  }
  throw RtdeError("a recipe with an unknown type");
}

}  // namespace

std::vector<std::uint8_t> dataPackage(std::uint8_t recipe_id, std::span<const RtdeValue> values) {
  std::vector<std::uint8_t> payload;
  wire::Writer w(payload);
  w.put(recipe_id);
  for (const RtdeValue& value : values) {
    std::visit(
        [&](const auto& v) {
          using Value = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<Value, bool>) {
            w.put(static_cast<std::uint8_t>(v ? 1 : 0));
          } else if constexpr (std::is_arithmetic_v<Value>) {
            w.put(v);
          } else {
            putArray(w, v);
          }
        },
        value);
  }
  return framePackage(PackageType::kDataPackage, payload);
}

std::uint8_t readRecipeId(std::span<const std::uint8_t> payload) {
  wire::Reader r(payload, "a data package");
  return r.get<std::uint8_t>();
}

std::vector<RtdeValue> readData(std::span<const std::uint8_t> payload,
                                std::span<const RtdeType> types) {
  wire::Reader r(payload, "a data package");
  r.get<std::uint8_t>();  // the recipe, which the caller chose `types` by
  std::size_t expected = 1;
  for (const RtdeType type : types) {
    expected += byteSize(type);
  }
  if (payload.size() != expected) {
    throw RtdeError("a data package of " + std::to_string(payload.size()) +
                    " bytes where its recipe makes " + std::to_string(expected));
  }
  std::vector<RtdeValue> values;
  values.reserve(types.size());
  for (const RtdeType type : types) {
    values.push_back(getValue(r, type));
  }
  r.end();
  return values;
}

std::vector<RtdeType> recipeTypes(const std::vector<std::string>& names, const SetupReply& reply) {
  if (reply.types.size() != names.size()) {
    throw RtdeError("the controller answered a recipe of " + std::to_string(names.size()) +
                    " variables with " + std::to_string(reply.types.size()) + " types");
  }
  std::vector<RtdeType> types;
  std::string refused;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (reply.types[i] == kNotFound) {
      refused += (refused.empty() ? "" : "; ") + names[i] + ": the controller has no such variable";
    } else if (reply.types[i] == kInUse) {
      refused += (refused.empty() ? "" : "; ") + names[i] + ": another RTDE client writes it";
    } else if (const std::optional<RtdeType> type = valueIn(kRtdeTypeNames, reply.types[i])) {
      types.push_back(*type);
    } else {
      refused +=
          (refused.empty() ? "" : "; ") + names[i] + ": an unknown type \"" + reply.types[i] + "\"";
    }
  }
  if (!refused.empty()) {
    throw RtdeError("recipe refused: " + refused);
  }
  return types;
}

}  // namespace comply::ur
