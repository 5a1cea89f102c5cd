// RTDE's packages byte for byte as the protocol lays them out (big-endian, a 3-byte header), both
// ways, and what is refused.

#include <gtest/gtest.h>

#include "comply/ur/rtde_packages.hpp"

namespace comply::ur {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes payloadOf(const Bytes& package) {
  return {package.begin() + static_cast<std::ptrdiff_t>(kHeaderBytes), package.end()};
}

std::string refusal(const auto& call) {
  try {
    call();
  } catch (const RtdeError& error) {
    return error.what();
  }
  return "accepted";
}

TEST(RtdePackages, ControlRequestsAreTheirBytes) {
  EXPECT_EQ(protocolVersionRequest(), (Bytes{0x00, 0x05, 'V', 0x00, 0x02}));
  EXPECT_EQ(controllerVersionRequest(), (Bytes{0x00, 0x03, 'v'}));
  EXPECT_EQ(startRequest(), (Bytes{0x00, 0x03, 'S'}));
  EXPECT_EQ(pauseRequest(), (Bytes{0x00, 0x03, 'P'}));
  const Bytes outputs = setupOutputsRequest({500.0, {"timestamp", "actual_q"}});
  Bytes expected{0x00, 0x1d, 'O', 0x40, 0x7f, 0x40, 0, 0, 0, 0, 0};  // 500.0 as IEEE 754
  for (const char c : std::string("timestamp,actual_q")) {
    expected.push_back(static_cast<std::uint8_t>(c));
  }
  EXPECT_EQ(outputs, expected);
  const Bytes inputs = setupInputsRequest({"input_double_register_24"});
  EXPECT_EQ(inputs.size(), 3U + 24U);
  EXPECT_EQ(inputs[2], 'I');
}

TEST(RtdePackages, RequestsAndAnswersReadBack) {
  EXPECT_EQ(readProtocolVersionRequest(payloadOf(protocolVersionRequest(7))), 7);
  const SetupOutputsRequest request =
      readSetupOutputsRequest(payloadOf(setupOutputsRequest({125.0, {"a", "b", "c"}})));
  EXPECT_EQ(request.frequency_hz, 125.0);
  EXPECT_EQ(request.names, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(readSetupInputsRequest(payloadOf(setupInputsRequest({"x"}))),
            std::vector<std::string>{"x"});
  EXPECT_TRUE(readAccepted(payloadOf(acceptedReply(PackageType::kStart, true))));
  EXPECT_FALSE(readAccepted(payloadOf(acceptedReply(PackageType::kStart, false))));
  const Bytes version = controllerVersionReply({5, 23, 1, 1234});
  EXPECT_EQ(version.size(), 3U + 16U);
  EXPECT_EQ((Bytes{version.begin() + 3, version.begin() + 7}), (Bytes{0, 0, 0, 5}));
  const ControllerVersion read = readControllerVersion(payloadOf(version));
  EXPECT_EQ(read.minor, 23U);
  EXPECT_EQ(read.build, 1234U);
  const SetupReply reply = readSetupReply(
      payloadOf(setupReply(PackageType::kSetupOutputs, {3, {"DOUBLE", "VECTOR6D"}})));
  EXPECT_EQ(reply.recipe_id, 3);
  EXPECT_EQ(reply.types, (std::vector<std::string>{"DOUBLE", "VECTOR6D"}));
  const Bytes text = textMessagePackage({"protective stop", "comply", TextLevel::kError});
  EXPECT_EQ(text[3], 15);  // the message's length, one byte
  const TextMessage message = readTextMessage(payloadOf(text));
  EXPECT_EQ(message.message, "protective stop");
  EXPECT_EQ(message.source, "comply");
  EXPECT_EQ(message.level, TextLevel::kError);
}

TEST(RtdeData, EveryTypeIsItsBigEndianBytesAndReadsBack) {
  const std::vector<RtdeValue> values{true,
                                      std::uint8_t{200},
                                      std::uint32_t{0x01020304},
                                      std::uint64_t{0x0102030405060708},
                                      std::int32_t{-2},
                                      1.5,
                                      std::array<double, 3>{1, 2, 3},
                                      std::array<double, 6>{0.1, 0.2, 0.3, 0.4, 0.5, 0.6},
                                      std::array<std::int32_t, 6>{-1, 2, -3, 4, -5, 6},
                                      std::array<std::uint32_t, 6>{1, 2, 3, 4, 5, 6}};
  const Bytes package = dataPackage(9, values);
  std::size_t size = kHeaderBytes + 1;
  std::vector<RtdeType> types;
  for (const RtdeValue& value : values) {
    types.push_back(typeOf(value));
    size += byteSize(typeOf(value));
  }
  ASSERT_EQ(package.size(), size);
  EXPECT_EQ(package[2], 'U');
  EXPECT_EQ(package[3], 9);
  EXPECT_EQ((Bytes{package.begin() + 4, package.begin() + 10}),
            (Bytes{0x01, 200, 0x01, 0x02, 0x03, 0x04}));
  EXPECT_EQ((Bytes{package.begin() + 10, package.begin() + 18}), (Bytes{1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ((Bytes{package.begin() + 18, package.begin() + 22}), (Bytes{0xff, 0xff, 0xff, 0xfe}));
  EXPECT_EQ((Bytes{package.begin() + 22, package.begin() + 30}),
            (Bytes{0x3f, 0xf8, 0, 0, 0, 0, 0, 0}));  // 1.5
  EXPECT_EQ(readRecipeId(payloadOf(package)), 9);
  EXPECT_EQ(readData(payloadOf(package), types), values);
}

TEST(RtdeData, EachTypesZeroTakesItsSize) {
  for (const auto& entry : kRtdeTypeNames) {
    const RtdeValue zero = zeroOf(entry.value);
    EXPECT_EQ(typeOf(zero), entry.value) << entry.name;
    EXPECT_EQ(dataPackage(0, {&zero, 1}).size(), kHeaderBytes + 1 + byteSize(entry.value))
        << entry.name;
  }
}

TEST(RtdeData, APayloadNotOfItsRecipeIsRefused) {
  const std::vector<RtdeValue> values{1.0, std::int32_t{1}};
  const Bytes payload = payloadOf(dataPackage(1, values));
  const std::vector<RtdeType> wrong{RtdeType::kDouble};
  EXPECT_EQ(refusal([&] { readData(payload, wrong); }),
            "a data package of 13 bytes where its recipe makes 9");
  Bytes bad_bool = payloadOf(dataPackage(1, std::vector<RtdeValue>{true}));
  bad_bool[1] = 2;
  const std::vector<RtdeType> boolean{RtdeType::kBool};
  EXPECT_EQ(refusal([&] { readData(bad_bool, boolean); }), "a data package's BOOL holds 2");
  EXPECT_EQ(refusal([&] { readData({}, boolean); }), "a data package: cut short (0 bytes)");
}

TEST(RtdeRecipes, TypesComeFromTheAnswerAndRefusalsNameTheirVariables) {
  EXPECT_EQ(recipeTypes({"timestamp", "actual_q"}, {1, {"DOUBLE", "VECTOR6D"}}),
            (std::vector<RtdeType>{RtdeType::kDouble, RtdeType::kVector6d}));
  EXPECT_EQ(refusal([] {
              recipeTypes({"actual_q", "bogus", "input_int_register_0"},
                          {1, {"VECTOR6D", "NOT_FOUND", "IN_USE"}});
            }),
            "recipe refused: bogus: the controller has no such variable; input_int_register_0: "
            "another RTDE client writes it");
  EXPECT_EQ(refusal([] {
              recipeTypes({"a"}, {1, {"QUATERNION"}});
            }),
            "recipe refused: a: an unknown type \"QUATERNION\"");
  EXPECT_EQ(refusal([] {
              recipeTypes({"a", "b"}, {1, {"DOUBLE"}});
            }),
            "the controller answered a recipe of 2 variables with 1 types");
  EXPECT_EQ(refusal([] { setupInputsRequest({"a,b"}); }),
            "a recipe's variable name must be non-empty and without a comma: \"a,b\"");
}

TEST(RtdePackages, OtherMalformedPackagesAreRefused) {
  EXPECT_EQ(refusal([] { readAccepted(Bytes{2}); }), "an accepted/refused answer of 2");
  EXPECT_EQ(refusal([] {
              readAccepted(Bytes{1, 0});
            }),
            "an accepted/refused answer: 1 bytes past its end");
  EXPECT_EQ(refusal([] { readTextMessage(Bytes{5, 'a'}); }), "a text message: cut short (2 bytes)");
  EXPECT_EQ(refusal([] { readTextMessage(Bytes{0, 0, 4}); }), "a text message of level 4");
  EXPECT_EQ(refusal([] {
              textMessagePackage({std::string(256, 'x'), "", TextLevel::kInfo});
            }),
            "a text message's message is longer than 255 bytes");
  EXPECT_EQ(refusal([] { framePackage(PackageType::kDataPackage, Bytes(65533, 0)); }),
            "an RTDE package of 65536 bytes: at most 65535 fit its header");
}

TEST(PackageFramer, PackagesComeOutWholeWhateverPiecesTheyArriveIn) {
  Bytes stream = protocolVersionRequest();
  const Bytes second = dataPackage(2, std::vector<RtdeValue>{1.25, std::int32_t{7}});
  stream.insert(stream.end(), second.begin(), second.end());
  for (const std::size_t piece : {std::size_t{1}, std::size_t{4}, stream.size()}) {
    PackageFramer framer;
    std::vector<Package> packages;
    for (std::size_t at = 0; at < stream.size(); at += piece) {
      const std::size_t size = std::min(piece, stream.size() - at);
      framer.feed(std::span(stream).subspan(at, size));
      for (Package package; framer.next(package);) {
        packages.push_back(package);
      }
    }
    ASSERT_EQ(packages.size(), 2U) << "pieces of " << piece;
    EXPECT_EQ(packages[0].type, PackageType::kRequestProtocolVersion);
    EXPECT_EQ(packages[0].payload, (Bytes{0x00, 0x02}));
    EXPECT_EQ(packages[1].type, PackageType::kDataPackage);
    EXPECT_EQ(packages[1].payload, payloadOf(second));
    EXPECT_EQ(framer.pending(), 0U);
  }
}

TEST(PackageFramer, AHeaderSmallerThanItselfLosesTheStream) {
  PackageFramer framer;
  framer.feed(Bytes{0x00, 0x02, 'U'});
  Package package;
  EXPECT_EQ(refusal([&] { framer.next(package); }),
            "an RTDE header gives a package of 2 bytes, less than the header: the stream is out "
            "of step");
}

}  // namespace
}  // namespace comply::ur
