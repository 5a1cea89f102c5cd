#include "schema_command.hpp"

#include <ostream>

#include "comply/schema/describe.hpp"
#include "comply/transport/message_text.hpp"

namespace comply::app {

int schemaCommand(const SchemaOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.message.empty()) {
    if (options.format != "msg" && options.format != "idl") {
      err << "comply schema: --message takes --format msg or idl\n";
      return 2;
    }
    const transport::MessageText message = transport::hostMessageText(options.message);
    out << (options.format == "msg" ? transport::rosMessageText(message)
                                    : transport::ddsIdlText(message));
    return 0;
  }
  const bool both = options.kind.empty();
  const schema::CommandKind kind =
      options.kind == "joint" ? schema::CommandKind::kJoint : schema::CommandKind::kCartesian;
  if (options.format == "markdown") {
    out << (both ? schema::markdownDocument() : schema::markdownTable(kind));
  } else if (options.format == "json") {
    out << (both ? schema::jsonDescription() : schema::jsonDescription(kind));
  } else if (options.format == "msg" && !both) {
    out << schema::rosMessage(kind);
  } else if (options.format == "idl" && !both) {
    out << schema::ddsIdl(kind);
  } else if (options.format == "msg" || options.format == "idl") {
    err << "comply schema: --format " << options.format
        << " needs --kind cartesian or --kind joint (one message)\n";
    return 2;
  } else {
    err << "comply schema: unknown --format '" << options.format
        << "' (markdown, json, msg, idl)\n";
    return 2;
  }
  return 0;
}

}  // namespace comply::app
