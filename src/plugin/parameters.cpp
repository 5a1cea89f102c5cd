#include "comply/plugin/parameters.hpp"

#include <cstring>

namespace comply::plugin {

const comply_parameter* Parameters::find(std::string_view name) const {
  if (parameters_ == nullptr) {
    return nullptr;
  }
  for (int32_t i = 0; i < parameters_->count; ++i) {
    const comply_parameter& item = parameters_->items[i];
    if (item.name != nullptr && name == item.name) {
      return &item;
    }
  }
  return nullptr;
}

double Parameters::number(std::string_view name, double fallback) const {
  const comply_parameter* item = find(name);
  if (item == nullptr) {
    return fallback;
  }
  if (item->values == nullptr || item->count != 1) {
    throw ParameterError("parameter '" + std::string(name) + "' must be one number");
  }
  return item->values[0];
}

std::span<const double> Parameters::numbers(std::string_view name, int expected_count) const {
  const comply_parameter* item = find(name);
  if (item == nullptr) {
    return {};
  }
  if (item->values == nullptr) {
    throw ParameterError("parameter '" + std::string(name) + "' must be a list of numbers");
  }
  if (item->count != expected_count) {
    throw ParameterError("parameter '" + std::string(name) + "' has " +
                         std::to_string(item->count) + " values, expected " +
                         std::to_string(expected_count));
  }
  return {item->values, static_cast<std::size_t>(item->count)};
}

std::string Parameters::text(std::string_view name, std::string_view fallback) const {
  const comply_parameter* item = find(name);
  if (item == nullptr) {
    return std::string(fallback);
  }
  if (item->text == nullptr) {
    throw ParameterError("parameter '" + std::string(name) + "' must be a string");
  }
  return item->text;
}

}  // namespace comply::plugin
