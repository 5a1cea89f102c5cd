#pragma once
// Commands as JSON objects (and YAML, through yamlToJson), with the schema's field names:
// quaternions [x, y, z, w], 3x3 gain blocks as 9 numbers row-major (or 3x3 nested), twists and
// wrenches linear first, damping_mode by name.
//
//   {"stamp": 0.1, "fields": ["stiffness"], "stiffness_translational": [...], ...}
//
// `fields` lists the field groups the command sets (schema::groups()); without it, the groups
// whose keys are present. Errors throw comply::InputError naming the key.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "comply/core/chunk.hpp"
#include "comply/schema/schema.hpp"

namespace YAML {
class Node;
}

namespace comply::schema {

template <typename Command>
struct ReadOptions {
  /// YAML-file shorthand: a 3x3 block as 1 number (isotropic) or 3 (diagonal), any vector as 1
  /// number for every entry.
  bool allow_shorthand = false;
  /// Values kept for absent keys; Command::zero(dof) without it.
  std::optional<Command> base;
  std::string source = "command";  ///< InputError::source(): file name, "command", ...
  std::string key_prefix;          ///< before each key in errors, e.g. "waypoints[2]."
};

template <typename Command>
struct Parsed {
  Command command;    ///< `fields`: the groups set (from `fields` or the keys present)
  FieldSet keys = 0;  ///< the table rows whose keys were present
};

template <typename Command>
Parsed<Command> fromJson(const nlohmann::json& object, int dof,
                         const ReadOptions<Command>& options = {});
extern template Parsed<CartesianCommand> fromJson(const nlohmann::json&, int,
                                                  const ReadOptions<CartesianCommand>&);
extern template Parsed<JointCommand> fromJson(const nlohmann::json&, int,
                                              const ReadOptions<JointCommand>&);

/// A timed chunk from {"chunk": [{"time": t, <command keys>}, ...]}: each waypoint is read as a
/// command on top of the one before it (`options.base` for the first), so a group given once
/// holds for the waypoints after it; the chunk's groups are those any waypoint sets. `time` [s] is
/// relative to `time_origin_s` (the chunk's stamp, or the observation it acts on). The stamp is
/// left to the caller. Errors (no `chunk` list, a waypoint without `time`, unknown keys) throw
/// InputError naming "chunk[k].<key>".
template <typename Command>
Chunk<Command> chunkFromJson(const nlohmann::json& object, int dof, double time_origin_s,
                             const ReadOptions<Command>& options = {});
extern template Chunk<CartesianCommand> chunkFromJson(const nlohmann::json&, int, double,
                                                      const ReadOptions<CartesianCommand>&);
extern template Chunk<JointCommand> chunkFromJson(const nlohmann::json&, int, double,
                                                  const ReadOptions<JointCommand>&);
/// Whether `object` is a chunk ({"chunk": [...]}) rather than a command.
bool isChunkJson(const nlohmann::json& object);

/// Every field, the stamp and the `fields` list; fromJson() reads it back bit for bit.
/// Deepest nesting of objects and arrays accepted in JSON input: commands and samples are a few
/// levels deep; a 100,000-level document used to overflow the stack of the recursive code after
/// the (iterative) parser.
inline constexpr int kMaxJsonDepth = 64;

/// Parses `text`, refusing nesting deeper than kMaxJsonDepth while parsing (InputError kSyntax
/// naming `source`); other syntax errors are nlohmann::json::parse_error as from json::parse.
nlohmann::json parseJson(const std::string& text, const std::string& source);

nlohmann::json toJson(const CartesianCommand& command);
nlohmann::json toJson(const JointCommand& command);

/// A YAML value as JSON: numbers as doubles (refusing NaN and infinity), other scalars as
/// strings. `where` names the value in errors ("task.waypoints[0]").
nlohmann::json yamlToJson(const YAML::Node& node, const std::string& source,
                          const std::string& where);

/// The commands a controller starts from (the `initial:` block of a controller file).
struct InitialCommands {
  JointCommand joint;
  CartesianCommand cartesian;
};

/// Defaults for `dof` joints: joint 100 N m/rad and 10 N m s/rad; Cartesian 500 N/m, 30 N m/rad,
/// 45 N s/m, 3 N m s/rad (isotropic), ratio damping with ratio 1, nullspace 2 N m/rad and
/// 0.5 N m s/rad.
InitialCommands defaultInitialCommands(int dof);

/// Reads an `initial`-style object (shorthand allowed) on top of defaultInitialCommands(dof).
/// Its keys are the fields of either table that the reference rules leave alone (gains, damping
/// mode and ratios, task frame, feedforwards); a key of both tables (torque_feedforward) sets
/// both. The result is checked (schema::checkFields, quaternion tolerance 1e-6); errors throw
/// InputError with `source` and `key_prefix` + key.
InitialCommands readInitialCommands(const nlohmann::json& object, int dof,
                                    const std::string& source,
                                    const std::string& key_prefix = "initial.");

}  // namespace comply::schema
