#pragma once
// `comply schema`: the command schema as a markdown table, JSON or ROS 2 .msg text, generated from
// the field tables (include/comply/schema/table.hpp); with --message, a host message's .msg or
// IDL from its table (include/comply/transport/message_tables.hpp).

#include <iosfwd>
#include <string>

namespace comply::app {

struct SchemaOptions {
  std::string format = "markdown";  ///< markdown | json | msg
  std::string kind;                 ///< cartesian | joint; empty: both (msg needs one)
  std::string message;              ///< ControllerState | CommandOutcome | Diagnostics (msg, idl)
};

/// Prints it; returns the exit code (0 ok, 2 bad options).
int schemaCommand(const SchemaOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
