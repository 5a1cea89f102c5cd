#pragma once
// One writer and one reader of a message type on a loopback participant in a random domain, so
// that parallel test runs do not hear each other.

#include <dds/dds.h>
#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "comply/transport/endpoints.hpp"

namespace comply::transport {

inline int testDomain() {
  std::random_device random;
  return 100 + static_cast<int>(random() % 100);
}

/// The next sample `reader` holds, as the CDR bytes CycloneDDS serialised (header included); a
/// test failure and nothing when it holds none.
inline std::vector<std::uint8_t> takeSerialized(dds_entity_t reader) {
  ddsi_serdata* serdata = nullptr;
  dds_sample_info_t info;
  const dds_return_t count = dds_takecdr(reader, &serdata, 1, &info, DDS_ANY_STATE);
  EXPECT_EQ(count, 1);
  if (count != 1) {
    return {};
  }
  std::vector<std::uint8_t> bytes(ddsi_serdata_size(serdata));
  ddsi_serdata_to_ser(serdata, 0, bytes.size(), bytes.data());
  ddsi_serdata_unref(serdata);
  return bytes;
}

template <typename Message>
struct Loopback {
  explicit Loopback(const std::string& topic)
      : participant({.domain_id = testDomain()}),
        writer(participant, topic),
        reader(participant, topic) {}

  /// Writes `message` once the reader is matched and waits until the reader has it.
  void send(const Message& message) {
    EXPECT_TRUE(writer.waitForMatch(1, 5.0));
    EXPECT_TRUE(writer.write(message));
    EXPECT_TRUE(reader.wait(5.0));
  }

  Participant participant;
  Writer<Message> writer;
  Reader<Message> reader;
};

}  // namespace comply::transport
