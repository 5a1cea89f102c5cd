// `comply send` and `comply echo`: a client of a host's topics.

#include "send_command.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <utility>

#include "comply/core/input_error.hpp"
#include "comply/core/text_file.hpp"
#include "comply/schema/json.hpp"
#include "comply/transport/endpoints.hpp"
#include "live_json.hpp"

namespace comply::app {
namespace {

using transport::Participant;

/// The host's first state message: its command kind and joints. Throws when none arrives.
transport::ControllerStateMessage hostState(Participant& participant, const ClientOptions& client) {
  transport::Reader<transport::ControllerStateMessage> reader(participant, client.name);
  std::vector<transport::Sample<transport::ControllerStateMessage>> samples;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(client.timeout_s);
  while (samples.empty() && std::chrono::steady_clock::now() < deadline) {
    reader.wait(0.1);
    reader.take(samples, nullptr, 1);
  }
  if (samples.empty()) {
    throw transport::TransportError("no host '" + client.name + "' on domain " +
                                    std::to_string(client.domain_id) + " within " +
                                    std::to_string(client.timeout_s) + " s (is `comply run` up?)");
  }
  return samples.front().message;
}

/// The commands of --json or --file: one object, a list, or JSON lines.
std::vector<nlohmann::json> commandObjects(const SendOptions& options) {
  if (!options.json.empty()) {
    return {schema::parseJson(options.json, "--json")};
  }
  const TextFile file = readTextFile(options.file);
  if (!file.ok()) {
    throw InputError(InputErrc::kCannotRead, options.file, "", file.error);
  }
  std::stringstream text(file.text);
  nlohmann::json all;
  const std::string name = options.file;
  if (name.ends_with(".yaml") || name.ends_with(".yml")) {
    all = schema::yamlToJson(YAML::Load(text.str()), name, "");
  } else if (!nlohmann::json::accept(text.str())) {
    std::vector<nlohmann::json> lines;  // JSON lines
    for (std::string line; std::getline(text, line);) {
      if (line.find_first_not_of(" \t\r") != std::string::npos) {
        lines.push_back(schema::parseJson(line, name));
      }
    }
    return lines;
  } else {
    all = schema::parseJson(text.str(), name);
  }
  return all.is_array() ? std::vector<nlohmann::json>(all.begin(), all.end())
                        : std::vector<nlohmann::json>{all};
}

/// Strictly increasing wall-clock stamps: the host refuses a stamp that is not newer.
transport::Stamp nextStamp(transport::Stamp& last) {
  transport::Stamp now = transport::Stamp::now();
  if (now <= last) {
    now = transport::Stamp::fromNanoseconds(last.nanoseconds() + 1);
  }
  last = now;
  return now;
}

/// The outcome of every command sent, printed as it arrives. Read while sending as well as after,
/// from a keep-all reader: a reader that looked only afterwards, keeping the last few diagnostics,
/// reported commands as lost that had been applied.
class OutcomeCollector {
 public:
  /// `noun`: what was sent, as the count of those without an outcome names them.
  OutcomeCollector(transport::Reader<transport::DiagnosticsMessage>& diagnostics,
                   const transport::Gid& sender, std::string noun = "commands")
      : diagnostics_(diagnostics), sender_(sender), noun_(std::move(noun)) {}

  void expect(std::int64_t stamp_ns) { sent_.emplace(stamp_ns, false); }
  /// Takes what has arrived; prints the outcomes of commands sent.
  void drain(std::ostream& out) {
    samples_.clear();
    diagnostics_.take(samples_, nullptr, 1000);
    for (const auto& sample : samples_) {
      for (const auto& outcome : sample.message.outcomes) {
        const auto it = sent_.find(outcome.stamp.nanoseconds());
        if (it == sent_.end() || it->second || !transport::sentBy(outcome, sender_)) {
          continue;
        }
        it->second = true;
        ++settled_;
        all_applied_ = all_applied_ && outcome.outcome == transport::Outcome::kApplied;
        out << outcomeLine(outcome) << "\n";
      }
    }
  }
  /// Waits for the rest; true when every command was applied.
  bool finish(double timeout_s, std::ostream& out) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (settled_ < sent_.size() && std::chrono::steady_clock::now() < deadline) {
      diagnostics_.wait(0.05);
      drain(out);
    }
    if (settled_ < sent_.size()) {
      out << (sent_.size() - settled_) << " of " << sent_.size() << " " << noun_
          << " without an outcome\n";
    }
    return all_applied_ && settled_ == sent_.size();
  }
  [[nodiscard]] std::size_t sent() const { return sent_.size(); }

 private:
  transport::Reader<transport::DiagnosticsMessage>& diagnostics_;
  transport::Gid sender_;
  std::string noun_;
  std::map<std::int64_t, bool> sent_;
  std::vector<transport::Sample<transport::DiagnosticsMessage>> samples_;
  std::size_t settled_ = 0;
  bool all_applied_ = true;
};

/// Sends probes until one has an outcome: the host's reader has then discovered this writer, so
/// no later message is dropped by discovery (a reader drops samples of a writer it does not know
/// yet). A command's probe has no field group (the host accounts it and changes nothing); a
/// request's is REQUEST_PROBE (nor does it take the command topics).
template <typename Message>
bool handshake(transport::Writer<Message>& writer,
               transport::Reader<transport::DiagnosticsMessage>& diagnostics, int dof,
               const transport::Gid& sender, transport::Stamp& last, double timeout_s) {
  std::vector<transport::Sample<transport::DiagnosticsMessage>> samples;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    Message probe;
    if constexpr (std::is_same_v<Message, transport::RequestMessage>) {
      probe.request = transport::RequestType::kProbe;
    } else {
      probe.command = decltype(probe.command)::zero(dof);
      probe.command.fields = CommandField::kNone;
    }
    probe.header.stamp = nextStamp(last);
    writer.write(probe);
    const auto wait_until = std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
    while (std::chrono::steady_clock::now() < wait_until) {
      diagnostics.wait(0.02);
      samples.clear();
      diagnostics.take(samples);
      for (const auto& sample : samples) {
        for (const auto& outcome : sample.message.outcomes) {
          if (outcome.stamp == probe.header.stamp && transport::sentBy(outcome, sender)) {
            return true;
          }
        }
      }
    }
  }
  return false;
}

/// How the i-th of `count` objects is read: on top of what is in force, named by its place.
template <typename Command>
schema::ReadOptions<Command> commandReadOptions(const SendOptions& options, std::size_t count,
                                                std::size_t i, const Command& in_force) {
  schema::ReadOptions<Command> read;
  read.source = options.file.empty() ? "--json" : options.file;
  read.allow_shorthand = true;  // typed by hand: a block as 1 or 3 numbers, a vector as 1
  read.key_prefix = count > 1 ? "[" + std::to_string(i) + "]." : "";
  read.base = in_force;
  return read;
}

template <typename Command>
void writeChunk(transport::Writer<transport::ChunkMessageOf<Command>>& writer,
                const transport::Stamp& stamp, Chunk<Command> chunk) {
  // A chunk's times are seconds after it is sent, on this machine's clock (the host's, on one
  // machine).
  transport::ChunkMessageOf<Command> message{{stamp, ""}, std::move(chunk)};
  for (ChunkWaypoint<Command>& waypoint : message.chunk.waypoints) {
    waypoint.time_s += stamp.seconds();
  }
  message.chunk.observation_s += stamp.seconds();  // NaN (not given) stays NaN
  message.chunk.takeover_s += stamp.seconds();
  writer.write(message);
}

template <typename Message>
int sendAll(Participant& participant, const SendOptions& options,
            const std::vector<nlohmann::json>& objects,
            const transport::ControllerStateMessage& state, std::ostream& out) {
  using Command = decltype(Message{}.command);
  using ChunkMessage = transport::ChunkMessageOf<Command>;
  const int dof = static_cast<int>(state.position.size());
  // A group given in part keeps the rest in force: the host's reference for the first command,
  // then what the command before it left (a stream of positions keeps the orientation).
  Command in_force = transport::referenceInForce<Command>(state, dof);
  // Keep-all both ways: at any --rate the writer waits for room rather than drop a command, and no
  // outcome is dropped before it is read.
  transport::Writer<Message> writer(participant, options.client.name, transport::kKeepAll);
  transport::Reader<transport::DiagnosticsMessage> diagnostics(participant, options.client.name,
                                                               transport::kKeepAll);
  // Chunks, when the file has any, on their own topic; reliable and keep-all, a chunk the host's
  // reader had not yet discovered is sent again until it is acknowledged.
  std::optional<transport::Writer<ChunkMessage>> chunk_writer;
  if (std::any_of(objects.begin(), objects.end(), schema::isChunkJson)) {
    chunk_writer.emplace(participant, options.client.name, transport::kKeepAll);
    if (!chunk_writer->waitForMatch(1, options.client.timeout_s)) {
      throw transport::TransportError("the host's chunk reader did not match");
    }
  }
  if (!writer.waitForMatch(1, options.client.timeout_s)) {
    throw transport::TransportError("the host's command reader did not match");
  }
  diagnostics.waitForMatch(1, options.client.timeout_s);
  transport::Stamp last;
  if (!handshake(writer, diagnostics, dof, participant.gid(), last, options.client.timeout_s)) {
    throw transport::TransportError("the host did not account a probe command");
  }
  const double rate_hz = options.rate_hz > 0.0 ? options.rate_hz : 100.0;
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / rate_hz));
  OutcomeCollector outcomes(diagnostics, participant.gid());
  auto next = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const schema::ReadOptions<Command> read =
        commandReadOptions(options, objects.size(), i, in_force);
    const bool chunk = schema::isChunkJson(objects[i]);
    // Read before the wait, so that a bad line stops the run before anything of it is sent.
    std::optional<Message> message;
    std::optional<Chunk<Command>> waypoints;
    if (chunk) {
      waypoints = schema::chunkFromJson<Command>(objects[i], dof, 0.0, read);
      in_force = waypoints->waypoints.back().command;
    } else {
      message = Message{{{}, ""}, schema::fromJson<Command>(objects[i], dof, read).command};
      in_force = message->command;
    }
    std::this_thread::sleep_until(next);
    next += period;
    const transport::Stamp stamp = nextStamp(last);
    if (chunk) {
      writeChunk(*chunk_writer, stamp, std::move(*waypoints));
    } else {
      message->header.stamp = stamp;
      writer.write(*message);
    }
    outcomes.expect(stamp.nanoseconds());
    if (!options.no_wait) {
      outcomes.drain(out);
    }
  }
  writer.flush(options.client.timeout_s);
  if (chunk_writer) {
    chunk_writer->flush(options.client.timeout_s);
  }
  out << "sent " << outcomes.sent() << " command" << (outcomes.sent() == 1 ? "" : "s") << "\n";
  if (options.no_wait) {
    return 0;
  }
  return outcomes.finish(options.client.timeout_s, out) ? 0 : 1;
}

/// A request, once the host has answered a probe from the same writer; then its outcome: carried
/// out (0), or refused with the reason or unanswered (1).
int sendRequest(Participant& participant, const SendOptions& options, std::ostream& out) {
  const auto request = valueIn(transport::kRequestTypeNames, options.request);
  if (!request) {
    throw std::invalid_argument("unknown request '" + options.request + "'");
  }
  transport::Writer<transport::RequestMessage> writer(participant, options.client.name);
  transport::Reader<transport::DiagnosticsMessage> diagnostics(participant, options.client.name,
                                                               transport::kKeepAll);
  if (!writer.waitForMatch(1, options.client.timeout_s)) {
    throw transport::TransportError("the host's request reader did not match");
  }
  diagnostics.waitForMatch(1, options.client.timeout_s);
  transport::Stamp last;
  if (!handshake(writer, diagnostics, 0, participant.gid(), last, options.client.timeout_s)) {
    throw transport::TransportError("the host did not account a probe request");
  }
  transport::RequestMessage message;
  message.header.stamp = nextStamp(last);
  message.request = *request;
  OutcomeCollector outcomes(diagnostics, participant.gid(), "requests");
  outcomes.expect(message.header.stamp.nanoseconds());
  writer.write(message);
  writer.flush(options.client.timeout_s);
  out << "sent request " << options.request << "\n";
  if (options.no_wait) {
    return 0;
  }
  return outcomes.finish(options.client.timeout_s, out) ? 0 : 1;
}

}  // namespace

transport::ParticipantOptions participantOptions(const ClientOptions& client) {
  return {
      .domain_id = client.domain_id,
      .network = client.network == "all" ? transport::Network::kAll : transport::Network::kLoopback,
      .security = client.security};
}

int sendCommand(const SendOptions& options, std::ostream& out, std::ostream& err) {
  const int given = (options.json.empty() ? 0 : 1) + (options.file.empty() ? 0 : 1) +
                    (options.request.empty() ? 0 : 1);
  if (given != 1) {
    err << "comply send: give exactly one of --json, --file and --request\n";
    return 2;
  }
  Participant participant(participantOptions(options.client));
  if (!options.request.empty()) {
    return sendRequest(participant, options, out);
  }
  const transport::ControllerStateMessage state = hostState(participant, options.client);
  const std::vector<nlohmann::json> objects = commandObjects(options);
  const bool joint = options.kind.empty() ? state.command_kind == transport::WireCommandKind::kJoint
                                          : options.kind == "joint";
  return joint ? sendAll<transport::JointCommandMessage>(participant, options, objects, state, out)
               : sendAll<transport::CartesianCommandMessage>(participant, options, objects, state,
                                                             out);
}

}  // namespace comply::app
