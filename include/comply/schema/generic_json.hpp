#pragma once
// JSON reading and writing, generic over a schema (see generic.hpp). Include only from .cpp files
// and tests.

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "comply/core/input_error.hpp"
#include "comply/schema/generic.hpp"
#include "comply/schema/json.hpp"

namespace comply::schema::generic {

/// Names of an enum field's values in JSON; specialised per enum type.
template <typename E>
struct EnumNames;

template <>
struct EnumNames<DampingMode> {
  static constexpr std::array<std::pair<DampingMode, std::string_view>, 2> kNames{
      {{DampingMode::kAbsolute, "absolute"}, {DampingMode::kRatio, "ratio"}}};
};

/// Where a value sits, for InputError.
struct JsonWhere {
  const std::string& source;
  std::string key;   ///< prefix + key
  std::string name;  ///< the key alone, quoted in messages
  [[noreturn]] void fail(InputErrc code, const std::string& message) const {
    throw InputError(code, source, key, message);
  }
};

/// A number, a list of numbers, or a list of rows of numbers, flattened.
std::vector<double> flatNumbers(const nlohmann::json& value, bool allow_scalar,
                                const JsonWhere& where);

/// Fills `value` of kind K from `numbers` (`count` = its entries; shorthand already checked).
template <FieldKind K, typename Value>
void fromNumbers(const std::vector<double>& n, int count, Value& value) {
  if constexpr (K == FieldKind::kQuaternion) {
    value = fromXyzw(n.data());  // not normalised: validation decides about drift
  } else if constexpr (K == FieldKind::kBlock3) {
    if (n.size() == 9) {
      value = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(n.data());
    } else {
      value =
          Eigen::Vector3d(n[0], n[n.size() == 3 ? 1 : 0], n[n.size() == 3 ? 2 : 0]).asDiagonal();
    }
  } else {
    if constexpr (K == FieldKind::kJointVector) {
      value.resize(count);
    }
    for (int i = 0; i < count; ++i) {
      value[i] = n.size() == 1 ? n[0] : n[static_cast<std::size_t>(i)];
    }
  }
}

template <FieldKind K, typename Value>
void readValue(const nlohmann::json& json, Value& value, int dof, bool shorthand,
               const JsonWhere& where) {
  if constexpr (K == FieldKind::kEnum) {
    using Names = EnumNames<Value>;
    std::string known;
    for (const auto& [enumerator, name] : Names::kNames) {
      if (json.is_string() && json.get<std::string>() == name) {
        value = enumerator;
        return;
      }
      known += std::string(known.empty() ? "" : " or ") + "\"" + std::string(name) + "\"";
    }
    where.fail(InputErrc::kInvalidValue, "'" + where.name + "' must be " + known);
  } else {
    const std::vector<double> n = flatNumbers(json, shorthand, where);
    const int count = K == FieldKind::kJointVector ? dof : fixedSize<K>();
    const auto size = static_cast<int>(n.size());
    const bool short_ok = shorthand && K != FieldKind::kQuaternion &&
                          (size == 1 || (K == FieldKind::kBlock3 && size == 3));
    if (size != count && !short_ok) {
      std::string expected = std::to_string(count);
      if (shorthand && K != FieldKind::kQuaternion) {
        expected = K == FieldKind::kBlock3 ? "1, 3 or 9" : "1 or " + expected;
      }
      where.fail(InputErrc::kWrongSize, "'" + where.name + "' has " + std::to_string(size) +
                                            " numbers, expected " + expected);
    }
    fromNumbers<K>(n, count, value);
  }
}

template <FieldKind K, typename Value>
nlohmann::json writeValue(const Value& value) {
  if constexpr (K == FieldKind::kEnum) {
    for (const auto& [enumerator, name] : EnumNames<Value>::kNames) {
      if (enumerator == value) {
        return std::string(name);
      }
    }
    return static_cast<std::int64_t>(value);  // not a named value: validation refuses it
  } else if constexpr (K == FieldKind::kQuaternion) {
    return nlohmann::json::array({value.x(), value.y(), value.z(), value.w()});
  } else if constexpr (K == FieldKind::kBlock3) {
    nlohmann::json rows = nlohmann::json::array();
    for (int k = 0; k < 9; ++k) {
      rows.push_back(value(k / 3, k % 3));
    }
    return rows;
  } else {
    nlohmann::json list = nlohmann::json::array();
    for (Eigen::Index i = 0; i < value.size(); ++i) {
      list.push_back(value[i]);
    }
    return list;
  }
}

/// `stamp` and `fields` of a command object; `present` are the groups of the keys given.
void readHeader(const nlohmann::json& object, CommandField present, const JsonWhere& where,
                double& stamp, CommandField& fields);
nlohmann::json groupNames(CommandField fields);

template <typename Schema>
std::string knownKeys() {
  std::string known = "stamp, fields";
  forEachField<Schema>([&](const auto& f, std::size_t) { known += ", " + std::string(f.name); });
  return known;
}

template <typename Schema>
Parsed<typename Schema::Command> fromJson(const nlohmann::json& object, int dof,
                                          const ReadOptions<typename Schema::Command>& options) {
  using Command = typename Schema::Command;
  const JsonWhere top{options.source, options.key_prefix, ""};
  if (!object.is_object()) {
    top.fail(InputErrc::kWrongType, "a command must be a JSON object");
  }
  Parsed<Command> parsed{options.base ? *options.base : Command::zero(dof), 0};
  CommandField present = CommandField::kNone;
  for (const auto& item : object.items()) {
    // Named references, not a structured binding: clang 14 cannot capture one in the lambda.
    const std::string& key = item.key();
    const nlohmann::json& value = item.value();
    if (key == "stamp" || key == "fields") {
      continue;
    }
    const JsonWhere where{options.source, options.key_prefix + key, key};
    const bool unknown = visitFields<Schema>([&](const auto& f, std::size_t index) {
      if (f.name != key) {
        return true;
      }
      readValue<FieldOf<decltype(f)>::kKind>(value, parsed.command.*f.member, dof,
                                             options.allow_shorthand, where);
      parsed.keys |= FieldSet{1} << index;
      present = present | f.group;
      return false;
    });
    if (unknown) {
      where.fail(InputErrc::kUnknownKey,
                 "unknown command field '" + key + "' (known: " + knownKeys<Schema>() + ")");
    }
  }
  readHeader(object, present, top, parsed.command.stamp_s, parsed.command.fields);
  return parsed;
}

template <typename Schema>
nlohmann::json toJson(const typename Schema::Command& command) {
  nlohmann::json object = nlohmann::json::object();
  object["stamp"] = command.stamp_s;
  object["fields"] = groupNames(command.fields);
  forEachField<Schema>([&](const auto& f, std::size_t) {
    object[std::string(f.name)] = writeValue<FieldOf<decltype(f)>::kKind>(command.*f.member);
  });
  return object;
}

}  // namespace comply::schema::generic
