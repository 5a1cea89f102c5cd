// RTDE's framing and control packages (see rtde_packages.hpp).

#include "comply/ur/rtde_packages.hpp"

#include "big_endian.hpp"

namespace comply::ur {
namespace {

std::vector<std::uint8_t> package(PackageType type, const std::vector<std::uint8_t>& payload) {
  return framePackage(type, payload);
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) {
    if (name.empty() || name.find(',') != std::string::npos) {
      throw RtdeError("a recipe's variable name must be non-empty and without a comma: \"" + name +
                      "\"");
    }
    text += (text.empty() ? "" : ",") + name;
  }
  return text;
}

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (start <= text.size() && !text.empty()) {
    const std::size_t comma = text.find(',', start);
    names.push_back(text.substr(start, comma == std::string::npos ? comma : comma - start));
    if (comma == std::string::npos) {
      break;
    }
    start = comma + 1;
  }
  return names;
}

/// A one-byte string length, then the string (text messages).
void putShortText(wire::Writer& w, const std::string& text, const char* what) {
  if (text.size() > 255) {
    throw RtdeError(std::string("a text message's ") + what + " is longer than 255 bytes");
  }
  w.put(static_cast<std::uint8_t>(text.size()));
  w.putText(text);
}

}  // namespace

std::vector<std::uint8_t> framePackage(PackageType type, std::span<const std::uint8_t> payload) {
  const std::size_t size = kHeaderBytes + payload.size();
  if (size > 0xffff) {
    throw RtdeError("an RTDE package of " + std::to_string(size) +
                    " bytes: at most 65535 fit its header");
  }
  std::vector<std::uint8_t> bytes;
  bytes.reserve(size);
  wire::Writer w(bytes);
  w.put(static_cast<std::uint16_t>(size));
  w.put(static_cast<std::uint8_t>(type));
  bytes.insert(bytes.end(), payload.begin(), payload.end());
  return bytes;
}

void PackageFramer::feed(std::span<const std::uint8_t> bytes) {
  if (start_ > 0 && start_ == buffer_.size()) {
    buffer_.clear();
    start_ = 0;
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
}

bool PackageFramer::next(Package& out) {
  if (pending() < kHeaderBytes) {
    return false;
  }
  const std::size_t size = (std::size_t{buffer_[start_]} << 8) | buffer_[start_ + 1];
  if (size < kHeaderBytes) {
    throw RtdeError("an RTDE header gives a package of " + std::to_string(size) +
                    " bytes, less than the header: the stream is out of step");
  }
  if (pending() < size) {
    return false;
  }
  out.type = static_cast<PackageType>(buffer_[start_ + 2]);
  out.payload.assign(buffer_.begin() + static_cast<std::ptrdiff_t>(start_ + kHeaderBytes),
                     buffer_.begin() + static_cast<std::ptrdiff_t>(start_ + size));
  start_ += size;
  if (start_ > 65536 && start_ * 2 > buffer_.size()) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
  }
  return true;
}

std::vector<std::uint8_t> protocolVersionRequest(std::uint16_t version) {
  std::vector<std::uint8_t> payload;
  wire::Writer(payload).put(version);
  return package(PackageType::kRequestProtocolVersion, payload);
}

std::vector<std::uint8_t> controllerVersionRequest() {
  return package(PackageType::kGetUrControlVersion, {});
}

std::vector<std::uint8_t> setupOutputsRequest(const SetupOutputsRequest& request) {
  std::vector<std::uint8_t> payload;
  wire::Writer w(payload);
  w.put(request.frequency_hz);
  w.putText(joined(request.names));
  return package(PackageType::kSetupOutputs, payload);
}

std::vector<std::uint8_t> setupInputsRequest(const std::vector<std::string>& names) {
  std::vector<std::uint8_t> payload;
  wire::Writer(payload).putText(joined(names));
  return package(PackageType::kSetupInputs, payload);
}

std::vector<std::uint8_t> startRequest() {
  return package(PackageType::kStart, {});
}

std::vector<std::uint8_t> pauseRequest() {
  return package(PackageType::kPause, {});
}

std::vector<std::uint8_t> acceptedReply(PackageType type, bool accepted) {
  return package(type, {static_cast<std::uint8_t>(accepted ? 1 : 0)});
}

std::vector<std::uint8_t> controllerVersionReply(const ControllerVersion& version) {
  std::vector<std::uint8_t> payload;
  wire::Writer w(payload);
  w.put(version.major);
  w.put(version.minor);
  w.put(version.bugfix);
  w.put(version.build);
  return package(PackageType::kGetUrControlVersion, payload);
}

std::vector<std::uint8_t> setupReply(PackageType type, const SetupReply& reply) {
  std::vector<std::uint8_t> payload;
  wire::Writer w(payload);
  w.put(reply.recipe_id);
  w.putText(joined(reply.types));
  return package(type, payload);
}

std::vector<std::uint8_t> textMessagePackage(const TextMessage& text) {
  std::vector<std::uint8_t> payload;
  wire::Writer w(payload);
  putShortText(w, text.message, "message");
  putShortText(w, text.source, "source");
  w.put(static_cast<std::uint8_t>(text.level));
  return package(PackageType::kTextMessage, payload);
}

std::uint16_t readProtocolVersionRequest(std::span<const std::uint8_t> payload) {
  wire::Reader r(payload, "a protocol version request");
  const auto version = r.get<std::uint16_t>();
  r.end();
  return version;
}

bool readAccepted(std::span<const std::uint8_t> payload) {
  wire::Reader r(payload, "an accepted/refused answer");
  const auto accepted = r.get<std::uint8_t>();
  r.end();
  if (accepted > 1) {
    throw RtdeError("an accepted/refused answer of " + std::to_string(accepted));
  }
  return accepted == 1;
}

ControllerVersion readControllerVersion(std::span<const std::uint8_t> payload) {
  wire::Reader r(payload, "a controller version");
  ControllerVersion version;
  version.major = r.get<std::uint32_t>();
  version.minor = r.get<std::uint32_t>();
  version.bugfix = r.get<std::uint32_t>();
  version.build = r.get<std::uint32_t>();
  r.end();
  return version;
}

SetupOutputsRequest readSetupOutputsRequest(std::span<const std::uint8_t> payload) {
  wire::Reader r(payload, "an output recipe's setup");
  SetupOutputsRequest request;
  request.frequency_hz = r.get<double>();
  request.names = split(r.rest());
  return request;
}

std::vector<std::string> readSetupInputsRequest(std::span<const std::uint8_t> payload) {
  wire::Reader r(payload, "an input recipe's setup");
  return split(r.rest());
}

SetupReply readSetupReply(std::span<const std::uint8_t> payload) {
  wire::Reader r(payload, "a recipe's setup answer");
  SetupReply reply;
  reply.recipe_id = r.get<std::uint8_t>();
  reply.types = split(r.rest());
  return reply;
}

TextMessage readTextMessage(std::span<const std::uint8_t> payload) {
  wire::Reader r(payload, "a text message");
  TextMessage text;
  text.message = r.getText(r.get<std::uint8_t>());
  text.source = r.getText(r.get<std::uint8_t>());
  const auto level = r.get<std::uint8_t>();
  r.end();
  if (level > static_cast<std::uint8_t>(TextLevel::kInfo)) {
    throw RtdeError("a text message of level " + std::to_string(level));
  }
  text.level = static_cast<TextLevel>(level);
  return text;
}

}  // namespace comply::ur
