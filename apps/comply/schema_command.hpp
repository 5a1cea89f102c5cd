#pragma once
// `comply schema`: the command schema as a markdown table, JSON or ROS 2 .msg text, generated from
// the field tables (include/comply/schema/table.hpp).

#include <iosfwd>
#include <string>

namespace comply::app {

struct SchemaOptions {
  std::string format = "markdown";  ///< markdown | json | msg
  std::string kind;                 ///< cartesian | joint; empty: both (msg needs one)
};

/// Prints it; returns the exit code (0 ok, 2 bad options).
int schemaCommand(const SchemaOptions& options, std::ostream& out, std::ostream& err);

}  // namespace comply::app
