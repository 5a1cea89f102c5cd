#pragma once
// The packages of Universal Robots' Real-Time Data Exchange (RTDE, protocol version 2), as the
// controller serves them on TCP port 30004: a 3-byte header (the package's size including the
// header, big-endian uint16, then its type) and a payload. A client asks for the protocol
// version, sets up an output recipe (the variables it wants, and how often) and input recipes
// (the registers it writes), starts, then reads data packages of its output recipe and writes
// data packages of its input recipes. Both sides are here: comply's UR backend is a client, its
// UR controller emulator a server. Everything is big-endian.

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "comply/ur/rtde_types.hpp"

namespace comply::ur {

/// A package that is not what its type says (cut short, a field out of range), a stream that
/// lost its framing, a recipe the controller refused.
class RtdeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class PackageType : std::uint8_t {
  kRequestProtocolVersion = 86,  // 'V'
  kGetUrControlVersion = 118,    // 'v'
  kTextMessage = 77,             // 'M'
  kDataPackage = 85,             // 'U'
  kSetupOutputs = 79,            // 'O'
  kSetupInputs = 73,             // 'I'
  kStart = 83,                   // 'S'
  kPause = 80,                   // 'P'
};

inline constexpr std::uint16_t kRtdeProtocolVersion = 2;
inline constexpr std::uint16_t kRtdePort = 30004;
inline constexpr std::size_t kHeaderBytes = 3;

/// One package: its type and what follows the header.
struct Package {
  PackageType type = PackageType::kDataPackage;
  std::vector<std::uint8_t> payload;
};

/// The package's bytes. Throws RtdeError when it would be longer than a package can say (65535).
std::vector<std::uint8_t> framePackage(PackageType type, std::span<const std::uint8_t> payload);

/// Cuts a byte stream into packages, whatever pieces it arrives in.
class PackageFramer {
 public:
  void feed(std::span<const std::uint8_t> bytes);
  /// The next complete package; false while none is complete. Throws RtdeError when a header
  /// gives a size below the header's own (the stream's framing is lost).
  bool next(Package& out);
  /// Bytes received and not yet returned as a package.
  [[nodiscard]] std::size_t pending() const noexcept { return buffer_.size() - start_; }

 private:
  std::vector<std::uint8_t> buffer_;
  std::size_t start_ = 0;
};

struct ControllerVersion {
  std::uint32_t major = 0;
  std::uint32_t minor = 0;
  std::uint32_t bugfix = 0;
  std::uint32_t build = 0;
};

/// RTDE_TEXT_MESSAGE (protocol 2): a message, where it comes from, and its level.
enum class TextLevel : std::uint8_t { kException = 0, kError = 1, kWarning = 2, kInfo = 3 };
struct TextMessage {
  std::string message;
  std::string source;
  TextLevel level = TextLevel::kInfo;
};

struct SetupOutputsRequest {
  double frequency_hz = 0.0;
  std::vector<std::string> names;
};

/// A setup's answer: the recipe's id and each variable's type name (or kNotFound, kInUse).
struct SetupReply {
  std::uint8_t recipe_id = 0;
  std::vector<std::string> types;
};

// What a client sends.
std::vector<std::uint8_t> protocolVersionRequest(std::uint16_t version = kRtdeProtocolVersion);
std::vector<std::uint8_t> controllerVersionRequest();
std::vector<std::uint8_t> setupOutputsRequest(const SetupOutputsRequest& request);
std::vector<std::uint8_t> setupInputsRequest(const std::vector<std::string>& names);
std::vector<std::uint8_t> startRequest();
std::vector<std::uint8_t> pauseRequest();

// What a server answers.
/// The answer to a protocol version, start or pause request.
std::vector<std::uint8_t> acceptedReply(PackageType type, bool accepted);
std::vector<std::uint8_t> controllerVersionReply(const ControllerVersion& version);
std::vector<std::uint8_t> setupReply(PackageType type, const SetupReply& reply);
/// Either side may send one.
std::vector<std::uint8_t> textMessagePackage(const TextMessage& text);

/// A data package of recipe `recipe_id` holding `values` in the recipe's order.
std::vector<std::uint8_t> dataPackage(std::uint8_t recipe_id, std::span<const RtdeValue> values);

// Reading a package's payload; each throws RtdeError naming what is wrong.
std::uint16_t readProtocolVersionRequest(std::span<const std::uint8_t> payload);
bool readAccepted(std::span<const std::uint8_t> payload);
ControllerVersion readControllerVersion(std::span<const std::uint8_t> payload);
SetupOutputsRequest readSetupOutputsRequest(std::span<const std::uint8_t> payload);
std::vector<std::string> readSetupInputsRequest(std::span<const std::uint8_t> payload);
SetupReply readSetupReply(std::span<const std::uint8_t> payload);
TextMessage readTextMessage(std::span<const std::uint8_t> payload);
/// The recipe a data package is of.
std::uint8_t readRecipeId(std::span<const std::uint8_t> payload);
/// A data package's values, read as `types` (its recipe's); refused unless the payload holds
/// exactly those.
std::vector<RtdeValue> readData(std::span<const std::uint8_t> payload,
                                std::span<const RtdeType> types);

/// The types of a recipe set up for `names` from the controller's answer; throws RtdeError naming
/// every variable the controller does not have, or whose register another client writes.
std::vector<RtdeType> recipeTypes(const std::vector<std::string>& names, const SetupReply& reply);

}  // namespace comply::ur
