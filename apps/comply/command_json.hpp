#pragma once
// Commands as JSON objects, read by the schema's reader (comply/schema/json.hpp, which documents
// the format): these names stay for the callers of `comply validate` and its tests.

#include <nlohmann/json_fwd.hpp>

#include "comply/core/input_error.hpp"
#include "comply/schema/json.hpp"

namespace comply::app {

/// Unknown keys, wrong lengths, wrong types; the message names the key.
using CommandJsonError = InputError;

/// The command `object` sets on top of `base` (keys of a set group that are absent keep base's
/// values); `fields` is the groups it sets.
template <typename Command>
Command commandFromJson(const nlohmann::json& object, int dof, const Command& base) {
  schema::ReadOptions<Command> options;
  options.base = base;
  return schema::fromJson(object, dof, options).command;
}

}  // namespace comply::app
