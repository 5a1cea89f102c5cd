// JSON and YAML for the two real schemas, and the helpers the generic reader shares.

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "comply/core/input_error.hpp"
#include "comply/schema/generic_json.hpp"
#include "schemas.hpp"

namespace comply::schema {
namespace generic {

std::vector<double> flatNumbers(const nlohmann::json& value, bool allow_scalar,
                                const JsonWhere& where) {
  std::vector<double> numbers;
  const auto take = [&](const nlohmann::json& entry) {
    if (!entry.is_number()) {
      where.fail(InputErrc::kWrongType, "'" + where.name + "' must be " +
                                            (allow_scalar ? "a number or " : "") +
                                            "a list of numbers");
    }
    numbers.push_back(entry.get<double>());
  };
  if (value.is_number() && allow_scalar) {
    take(value);
    return numbers;
  }
  if (!value.is_array()) {
    take(nlohmann::json());  // fails with the message above
  }
  for (const nlohmann::json& entry : value) {
    if (entry.is_array()) {  // rows of a block
      for (const nlohmann::json& inner : entry) {
        take(inner);
      }
    } else {
      take(entry);
    }
  }
  return numbers;
}

void readHeader(const nlohmann::json& object, CommandField present, const JsonWhere& where,
                double& stamp, CommandField& fields) {
  const auto at = [&](const char* key) { return JsonWhere{where.source, where.key + key, key}; };
  if (object.contains("stamp")) {
    if (!object.at("stamp").is_number()) {
      at("stamp").fail(InputErrc::kWrongType, "'stamp' must be a number [s]");
    }
    stamp = object.at("stamp").get<double>();
  }
  fields = present;
  if (!object.contains("fields")) {
    return;
  }
  const nlohmann::json& list = object.at("fields");
  if (!list.is_array()) {
    at("fields").fail(InputErrc::kWrongType, "'fields' must be a list of field group names");
  }
  fields = CommandField::kNone;
  for (const nlohmann::json& name : list) {
    bool found = false;
    for (const GroupInfo& group : groups()) {
      if (name.is_string() && name.get<std::string>() == group.name) {
        fields = fields | group.field;
        found = true;
      }
    }
    if (!found) {
      at("fields").fail(InputErrc::kInvalidValue, "'fields' holds an unknown group " + name.dump());
    }
  }
}

nlohmann::json groupNames(CommandField fields) {
  nlohmann::json names = nlohmann::json::array();
  for (const GroupInfo& group : groups()) {
    if (has(fields, group.field)) {
      names.push_back(std::string(group.name));
    }
  }
  return names;
}

}  // namespace generic

template <typename Command>
Parsed<Command> fromJson(const nlohmann::json& object, int dof,
                         const ReadOptions<Command>& options) {
  return generic::fromJson<SchemaOf<Command>>(object, dof, options);
}
template Parsed<CartesianCommand> fromJson(const nlohmann::json&, int,
                                           const ReadOptions<CartesianCommand>&);
template Parsed<JointCommand> fromJson(const nlohmann::json&, int,
                                       const ReadOptions<JointCommand>&);

nlohmann::json toJson(const CartesianCommand& command) {
  return generic::toJson<CartesianSchema>(command);
}
nlohmann::json toJson(const JointCommand& command) {
  return generic::toJson<JointSchema>(command);
}

nlohmann::json yamlToJson(const YAML::Node& node, const std::string& source,
                          const std::string& where) {
  switch (node.Type()) {
    case YAML::NodeType::Sequence: {
      nlohmann::json array = nlohmann::json::array();
      for (std::size_t i = 0; i < node.size(); ++i) {
        array.push_back(yamlToJson(node[i], source, where + "[" + std::to_string(i) + "]"));
      }
      return array;
    }
    case YAML::NodeType::Map: {
      nlohmann::json object = nlohmann::json::object();
      for (const auto& entry : node) {
        const auto key = entry.first.as<std::string>();
        object[key] = yamlToJson(entry.second, source, where + "." + key);
      }
      return object;
    }
    case YAML::NodeType::Scalar: {
      double number = 0.0;
      if (YAML::convert<double>::decode(node, number)) {
        if (!std::isfinite(number)) {
          throw InputError(InputErrc::kOutOfRange, source, where,
                           "'" + node.Scalar() + "' is not a finite number");
        }
        return number;
      }
      return node.Scalar();
    }
    default:
      throw InputError(InputErrc::kMissingKey, source, where, "has no value");
  }
}

nlohmann::json parseJson(const std::string& text, const std::string& source) {
  const auto bounded = [&source](int depth, nlohmann::json::parse_event_t event, nlohmann::json&) {
    if ((event == nlohmann::json::parse_event_t::object_start ||
         event == nlohmann::json::parse_event_t::array_start) &&
        depth >= kMaxJsonDepth) {
      throw InputError(InputErrc::kSyntax, source, "",
                       "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    }
    return true;
  };
  return nlohmann::json::parse(text, bounded);
}

}  // namespace comply::schema
