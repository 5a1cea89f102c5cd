// chunkFromJson (schema/json.hpp): a chunk is a list of commands with times.

#include <nlohmann/json.hpp>
#include <utility>

#include "comply/core/input_error.hpp"
#include "comply/schema/json.hpp"

namespace comply::schema {

bool isChunkJson(const nlohmann::json& object) {
  return object.is_object() && object.contains("chunk");
}

template <typename Command>
Chunk<Command> chunkFromJson(const nlohmann::json& object, int dof, double time_origin_s,
                             const ReadOptions<Command>& options) {
  const std::string prefix = options.key_prefix + "chunk";
  if (!object.is_object() || !object.contains("chunk") || !object.at("chunk").is_array()) {
    throw InputError(InputErrc::kMissingKey, options.source, prefix,
                     "a chunk is {\"chunk\": [{\"time\": s, <command keys>}, ...]}");
  }
  for (const auto& [key, value] : object.items()) {
    if (key != "chunk" && key != "stamp" && key != "observation" && key != "takeover") {
      throw InputError(InputErrc::kUnknownKey, options.source, options.key_prefix + key,
                       "a chunk has only `chunk` (and `stamp`, `observation`, `takeover`); each "
                       "waypoint carries its keys");
    }
  }
  Chunk<Command> chunk;
  // Optional times [s] on the waypoints' origin: the observation it was planned for, and when it
  // takes over from the running chunk (absent: not said, at once).
  for (const auto& [key, time_s] :
       {std::pair{"observation", &chunk.observation_s}, std::pair{"takeover", &chunk.takeover_s}}) {
    if (!object.contains(key)) {
      continue;
    }
    if (!object.at(key).is_number()) {
      throw InputError(InputErrc::kWrongType, options.source, options.key_prefix + key,
                       "a time [s] (a number), on the waypoints' origin");
    }
    *time_s = time_origin_s + object.at(key).template get<double>();
  }
  chunk.fields = CommandField::kNone;
  ReadOptions<Command> read = options;
  if (!read.base) {
    read.base = Command::zero(dof);
  }
  std::size_t k = 0;
  for (const nlohmann::json& entry : object.at("chunk")) {
    read.key_prefix = prefix + "[" + std::to_string(k++) + "].";
    if (!entry.is_object() || !entry.contains("time") || !entry.at("time").is_number()) {
      throw InputError(InputErrc::kMissingKey, options.source, read.key_prefix + "time",
                       "every waypoint has a time [s] (a number)");
    }
    nlohmann::json command = entry;
    command.erase("time");
    Command waypoint = fromJson<Command>(command, dof, read).command;
    chunk.fields = chunk.fields | waypoint.fields;
    read.base = waypoint;
    chunk.waypoints.push_back({time_origin_s + entry.at("time").get<double>(), waypoint});
  }
  return chunk;
}

template Chunk<CartesianCommand> chunkFromJson(const nlohmann::json&, int, double,
                                               const ReadOptions<CartesianCommand>&);
template Chunk<JointCommand> chunkFromJson(const nlohmann::json&, int, double,
                                           const ReadOptions<JointCommand>&);

}  // namespace comply::schema
