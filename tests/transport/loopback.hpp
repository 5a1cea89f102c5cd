#pragma once
// One writer and one reader of a message type on a loopback participant in a random domain, so
// that parallel test runs do not hear each other.

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "comply/transport/endpoints.hpp"

namespace comply::transport {

inline int testDomain() {
  std::random_device random;
  return 100 + static_cast<int>(random() % 100);
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
