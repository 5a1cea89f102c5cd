// Fuzz target: one DDS sample as it arrives in a DATA submessage, decoded the way a comply_msgs
// reader decodes it. CycloneDDS checks the CDR bytes against the type (dds_stream_normalize_data),
// reads them into the generated C struct (dds_stream_read), then the transport turns the struct
// into a message (wire::Wire<Message>::read) and a command is checked field by field, as
// `comply run` does before a command can reach the controller.
//
// Input: byte 0 picks the topic type; the rest is the serialised sample, starting with its
// 4-byte encapsulation header (encoding identifier, big-endian, then 2 option bytes).
#include <dds/dds.h>
#include <dds/ddsi/ddsi_cdrstream.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "comply/schema/schema.hpp"
#include "comply/transport/messages.hpp"
#include "wire.hpp"

namespace {

using namespace comply::transport;  // NOLINT(google-build-using-namespace): test-only brevity

// Encoding identifiers of DDS-XTypes 7.6.3.1.2 that a final (non-mutable) type can arrive in.
constexpr std::uint16_t kCdrBigEndian = 0x0000;
constexpr std::uint16_t kCdrLittleEndian = 0x0001;
constexpr std::uint16_t kCdr2BigEndian = 0x0006;
constexpr std::uint16_t kCdr2LittleEndian = 0x0007;
constexpr std::uint32_t kXcdr1 = 1;  // CycloneDDS's CDR_ENC_VERSION_1
constexpr std::uint32_t kXcdr2 = 2;
// Larger than any comply message (a 12-joint Cartesian command is about 1.2 kB) and than the
// 64 kB a UDP datagram holds unfragmented.
constexpr std::size_t kMaxSampleBytes = 1U << 17U;

template <typename Message>
void check(Message& /*message*/) {}

template <>
void check(CartesianCommandMessage& message) {
  (void)comply::schema::checkFields(message.command, 7);
}

template <>
void check(JointCommandMessage& message) {
  (void)comply::schema::checkFields(message.command, 6);
}

template <typename Message>
void decode(const std::uint8_t* data, std::size_t size) {
  if (size < 4 || size > kMaxSampleBytes) {
    return;
  }
  const auto encoding = static_cast<std::uint16_t>((data[0] << 8U) | data[1]);
  bool big_endian = false;
  std::uint32_t xcdr_version = 0;
  switch (encoding) {
    case kCdrBigEndian:
    case kCdrLittleEndian:
      xcdr_version = kXcdr1;
      big_endian = encoding == kCdrBigEndian;
      break;
    case kCdr2BigEndian:
    case kCdr2LittleEndian:
      xcdr_version = kXcdr2;
      big_endian = encoding == kCdr2BigEndian;
      break;
    default:
      return;  // CycloneDDS drops a sample in an encoding it does not read
  }
  // The body is normalised in place and read with aligned loads: a copy of exactly its bytes, on
  // the heap (aligned to 16), so that AddressSanitizer sees any access past them. (An earlier
  // harness left zeroed room after the copy and so hid CycloneDDS 0.10's own over-read and
  // byte-swap past a malformed XCDR2 sample: tests/fuzz/upstream/dds_sample/ keeps those inputs,
  // and `comply run` survives it by running DDS in a process of its own.)
  const auto body_size = static_cast<std::uint32_t>(size - 4);
  const std::unique_ptr<char[]> body(new char[body_size]);
  std::memcpy(body.get(), data + 4, body_size);
  char* bytes = body.get();

  const dds_topic_descriptor_t* descriptor = comply::transport::wire::Wire<Message>::descriptor();
  std::uint32_t offset = 0;
  const bool byte_swap = big_endian == (DDSRT_ENDIAN == DDSRT_LITTLE_ENDIAN);
  if (dds_stream_normalize_data(bytes, &offset, body_size, byte_swap, xcdr_version,
                                descriptor->m_ops) == nullptr) {
    return;  // refused by the type check, as the reader would refuse it
  }
  void* sample = std::calloc(1, descriptor->m_size);
  dds_istream_t stream;
  dds_istream_init(&stream, body_size, bytes, xcdr_version);
  dds_stream_read(&stream, static_cast<char*>(sample), descriptor->m_ops);

  comply::transport::Sample<Message> read;
  comply::transport::wire::Wire<Message>::read(sample, read);
  if (read.malformed.empty()) {
    check(read.message);
  }
  dds_stream_free_sample(sample, descriptor->m_ops);
  std::free(sample);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) {
    return 0;
  }
  try {
    using Decode = void (*)(const std::uint8_t*, std::size_t);
    constexpr Decode kDecoders[] = {decode<CartesianCommandMessage>, decode<JointCommandMessage>,
                                    decode<RequestMessage>, decode<ControllerStateMessage>,
                                    decode<DiagnosticsMessage>};
    kDecoders[data[0] % std::size(kDecoders)](data + 1, size - 1);
  } catch (const std::exception&) {
    // A refusal with a message is an expected outcome; a crash is not.
  }
  return 0;
}
