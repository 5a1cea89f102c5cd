// The option table as typed, flat parameters (config_parameters.hpp).

#include "comply/pipeline/config_parameters.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "comply/core/input_error.hpp"
#include "config_options.hpp"

namespace comply::pipeline {
namespace {

ParameterType typeOf(options::Kind kind) {
  switch (kind) {
    case options::Kind::kFlag:
      return ParameterType::kBool;
    case options::Kind::kChoice:
      return ParameterType::kString;
    case options::Kind::kVector3:
    case options::Kind::kPerJoint:
      return ParameterType::kDoubleList;
    case options::Kind::kNumber:
      break;
  }
  return ParameterType::kDouble;
}

ParameterValue typed(options::Kind kind, const options::Value& value) {
  switch (typeOf(kind)) {
    case ParameterType::kBool:
      return value.flag;
    case ParameterType::kString:
      return value.text;
    case ParameterType::kDoubleList:
      return value.numbers;
    case ParameterType::kDouble:
      break;
  }
  return value.number;
}

/// A parameter's value as the YAML scalar or sequence a controller file would hold.
YAML::Node yamlOf(const ParameterValue& value) {
  return std::visit(
      [](const auto& held) -> YAML::Node {
        using Held = std::decay_t<decltype(held)>;
        if constexpr (std::is_same_v<Held, std::monostate>) {
          return YAML::Node(YAML::NodeType::Undefined);
        } else if constexpr (std::is_same_v<Held, std::vector<bool>>) {
          YAML::Node list(YAML::NodeType::Sequence);
          for (const bool entry : held) {
            list.push_back(entry);
          }
          return list;
        } else {
          return YAML::Node(held);
        }
      },
      value);
}

/// The lists of maps a controller file may hold (walls, boxes): ROS 2 parameters hold no list of
/// maps, so these come as the YAML text of the list (`walls: "[{point: [0.65, 0, 0], normal:
/// [1, 0, 0]}]"`), read as the file's list would be.
bool isYamlList(const std::string& name) {
  return name == "walls" || name == "boxes";
}

YAML::Node yamlList(const FlatParameter& parameter, const std::string& source,
                    const std::string& key) {
  const auto* text = std::get_if<std::string>(&parameter.value);
  if (text == nullptr) {
    return yamlOf(parameter.value);
  }
  try {
    return YAML::Load(*text);
  } catch (const YAML::Exception& error) {
    throw InputError(InputErrc::kInvalidValue, source, key,
                     "is not the YAML text of a list (" + error.msg + ")");
  }
}

/// The nested mapping a controller file holds under ros__parameters, from dotted names.
YAML::Node nest(const std::vector<FlatParameter>& parameters, const std::string& source,
                const std::string& controller_name) {
  YAML::Node root(YAML::NodeType::Map);
  for (const FlatParameter& parameter : parameters) {
    if (std::holds_alternative<std::monostate>(parameter.value)) {
      continue;
    }
    const std::string key = controller_name + ".ros__parameters." + parameter.name;
    const std::vector<std::string> path = options::keyPath(parameter.name);
    if (path.empty() || std::find(path.begin(), path.end(), "") != path.end()) {
      throw InputError(InputErrc::kInvalidValue, source, key, "is not a parameter name");
    }
    YAML::Node node;
    node.reset(root);  // reset(), not '=': assigning a YAML::Node overwrites its target
    for (std::size_t depth = 0; depth + 1 < path.size(); ++depth) {
      YAML::Node next = node[path[depth]];
      if (!next.IsDefined() || next.IsNull()) {
        next = YAML::Node(YAML::NodeType::Map);  // '=' on purpose: creates the section in place
      } else if (!next.IsMap()) {
        throw InputError(InputErrc::kInconsistent, source, key,
                         "lies under a parameter that has a value of its own");
      }
      node.reset(next);
    }
    if (node[path.back()].IsMap()) {
      throw InputError(InputErrc::kInconsistent, source, key,
                       "has a value and parameters under it");
    }
    node[path.back()] = isYamlList(parameter.name) ? yamlList(parameter, source, key)
                                                   : yamlOf(parameter.value);
  }
  return root;
}

}  // namespace

std::vector<OptionDeclaration> optionDeclarations() {
  std::vector<OptionDeclaration> declarations;
  for (const options::Option& option : options::table()) {
    OptionDeclaration declaration;
    declaration.name = option.key;
    declaration.type = typeOf(option.kind);
    if (option.hasDefault()) {
      declaration.default_value = typed(option.kind, option.default_value);
    }
    declaration.description = option.comment;
    declaration.constraint = options::constraintText(option);
    declaration.min = option.min <= -1e300 ? std::numeric_limits<double>::lowest() : option.min;
    declaration.max = option.max >= 1e300 ? std::numeric_limits<double>::max() : option.max;
    declaration.choices = option.choices;
    declarations.push_back(std::move(declaration));
  }
  return declarations;
}

ParameterValue optionValue(const WrapperConfig& config, const std::string& name) {
  for (const options::Option& option : options::table()) {
    if (name == option.key) {
      return typed(option.kind, option.read(config));
    }
  }
  throw std::out_of_range("no option named '" + name + "'");
}

WrapperConfig parseWrapperParameters(const std::vector<FlatParameter>& parameters,
                                     const std::string& source,
                                     const std::string& controller_name) {
  return options::parseParameters(nest(parameters, source, controller_name), source,
                                  controller_name);
}

}  // namespace comply::pipeline
