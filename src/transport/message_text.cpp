// The host's messages as .msg and IDL text, from their tables (see message_text.hpp).

#include "comply/transport/message_text.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "comply/core/upper_case.hpp"

namespace comply::transport {
namespace {

/// PREFIX_NAME=value for each row of an enum's EnumNames table.
template <typename Enum, std::size_t N>
void addConstants(std::vector<ConstantText>& constants, std::string_view prefix,
                  const EnumNames<Enum, N>& names) {
  for (const auto& [value, name] : names) {
    constants.push_back({std::string(prefix) + upperCase(name), static_cast<int>(value), {}});
  }
}

MessageText controllerState() {
  MessageText message{"ControllerState",
                      "comply_msgs/ControllerState: what the controller host measured and "
                      "commanded, published at the\nhost's state rate on /<name>/state with the "
                      "sensor-data QoS (best effort, volatile, keep last 5).\nPoses and twists in "
                      "the robot's base frame.",
                      {},
                      fieldTexts<ControllerStateMessage>()};
  addConstants(message.constants, "STATE_", kWrapperStateNames);
  addConstants(message.constants, "COMMAND_KIND_", kWireCommandKindNames);
  addConstants(message.constants, "WRENCH_SOURCE_", kWrenchSourceNames);
  addConstants(message.constants, "REFLEX_", kReflexReactionNames);
  return message;
}

MessageText commandOutcome() {
  MessageText message{"CommandOutcome",
                      "comply_msgs/CommandOutcome: what became of one command (an entry of "
                      "Diagnostics.outcomes).\nEvery command the host receives gets exactly one: "
                      "applied by a control cycle, or rejected with\na reason. So does every "
                      "request (command_kind COMMAND_KIND_REQUEST): applied when the host\n"
                      "carried it out, or rejected.",
                      {},
                      fieldTexts<CommandOutcomeMessage>()};
  addConstants(message.constants, "OUTCOME_", kOutcomeNames);
  message.constants.push_back({"REASON_NONE", static_cast<int>(Reason::kNone), {}});
  for (std::size_t i = 0; i < kReasonCount; ++i) {
    const auto reason = static_cast<Reason>(i);
    message.constants.push_back({"REASON_" + upperCase(toString(reason)), static_cast<int>(i),
                                 std::string(kRejectionReasonDocs[i])});
  }
  return message;
}

MessageText chunkTiming() {
  MessageText message{"ChunkTiming",
                      "comply_msgs/ChunkTiming: what became of one accepted chunk in the cycle "
                      "(docs/chunks.md): when it\ntook over, how many of its waypoints were "
                      "already past, how far the reference jumped at the\nseam. In its "
                      "CommandOutcome.chunk, and one per chunk on a recording's /<name>/"
                      "chunk_timing.\nTimes on the host's clock (its state's header.stamp).",
                      {},
                      fieldTexts<ChunkTimingMessage>()};
  addConstants(message.constants, "END_", kChunkEndNames);
  return message;
}

MessageText diagnostics() {
  return {"Diagnostics",
          "comply_msgs/Diagnostics: the host's counters and the outcome of every command and "
          "request, on\n"
          "/<name>/diagnostics (reliable, volatile, keep last 100), whenever outcomes are waiting "
          "(at most\nevery 10 ms) and once a second otherwise. Counters run from the host's "
          "start.",
          {},
          fieldTexts<DiagnosticsMessage>()};
}

MessageText committedRequest() {
  return {"CommittedRequest",
          "comply_msgs/CommittedRequest: asks the host for the reference its cycles will write "
          "at\nobservation + k dt (k < count) if no new command or chunk arrives, on "
          "/<name>/committed_request\n(reliable, volatile, keep last 10): the actions a policy's "
          "next chunk may keep\n(docs/policies.md). The host answers each on /<name>/committed "
          "(comply_msgs/Committed), or\nrefuses it there naming the field (a step not > 0, a "
          "count of 0 or over 64).",
          {},
          fieldTexts<CommittedRequestMessage>()};
}

void comment(std::ostringstream& out, std::string_view text) {
  std::istringstream lines{std::string(text)};
  std::string line;
  while (std::getline(lines, line)) {
    out << "# " << line << "\n";
  }
}

}  // namespace

std::string rosMessageText(const MessageText& message) {
  std::ostringstream out;
  comment(out, message.about);
  comment(out,
          "Generated from include/comply/transport/message_tables.hpp by `make generated`;\n"
          "src/transport/idl/comply_msgs/msg/" +
              message.name + ".idl is its wire form.");
  out << "\n";
  for (const ConstantText& constant : message.constants) {
    out << "uint8 " << constant.name << "=" << constant.value
        << (constant.doc.empty() ? "" : "  # " + constant.doc) << "\n";
  }
  if (!message.constants.empty()) {
    out << "\n";
  }
  for (const FieldText& field : message.fields) {
    out << field.msg_type << " " << field.name << "  # " << field.doc << "\n";
  }
  return out.str();
}

std::string ddsIdlText(const MessageText& message) {
  const std::string guard = "COMPLY_MSGS__MSG__" + upperCase(message.name) + "_IDL";
  std::vector<std::string> includes;
  for (const FieldText& field : message.fields) {
    if (!field.idl_include.empty() &&
        std::find(includes.begin(), includes.end(), field.idl_include) == includes.end()) {
      includes.push_back(field.idl_include);
    }
  }
  std::sort(includes.begin(), includes.end());
  std::ostringstream out;
  out << "// comply_msgs/" << message.name << " (msg/" << message.name
      << ".msg) as ROS 2 (rosidl) puts it on the wire.\n"
      << "// Generated from include/comply/transport/message_tables.hpp by `make generated`.\n\n"
      << "#ifndef " << guard << "\n#define " << guard << "\n\n";
  for (const std::string& include : includes) {
    out << "#include \"" << include << "\"\n";
  }
  out << "\nmodule comply_msgs {\nmodule msg {\nmodule dds_ {\n\n";
  if (!message.constants.empty()) {
    out << "module " << message.name << "_Constants {\n";
    for (const ConstantText& constant : message.constants) {
      out << "const octet " << constant.name << " = " << constant.value << ";\n";
    }
    out << "};\n\n";
  }
  out << "struct " << message.name << "_ {\n";
  for (const FieldText& field : message.fields) {
    out << "  " << field.idl_type << " " << field.name << field.idl_suffix << ";\n";
  }
  out << "};\n\n};  // module dds_\n};  // module msg\n};  // module comply_msgs\n\n#endif  // "
      << guard << "\n";
  return out.str();
}

MessageText hostMessageText(std::string_view name) {
  if (name == "ControllerState") {
    return controllerState();
  }
  if (name == "CommandOutcome") {
    return commandOutcome();
  }
  if (name == "ChunkTiming") {
    return chunkTiming();
  }
  if (name == "Diagnostics") {
    return diagnostics();
  }
  if (name == "CommittedRequest") {
    return committedRequest();
  }
  throw std::out_of_range(
      "no host message named " + std::string(name) +
      " (ControllerState, CommandOutcome, ChunkTiming, Diagnostics, CommittedRequest)");
}

std::vector<std::string_view> hostMessageNames() {
  return {"ControllerState", "CommandOutcome", "ChunkTiming", "Diagnostics", "CommittedRequest"};
}

}  // namespace comply::transport
