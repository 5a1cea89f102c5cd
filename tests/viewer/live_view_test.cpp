// The host's live view: its address parsed, its channels, the control thread's side free of
// allocation with a viewer connected and without, and what a viewer then receives equal to what
// the control thread handed over.

#include "comply/host/live_view.hpp"

#include <gtest/gtest.h>

#include <thread>

#include "allocation_counter.hpp"
#include "comply/host/controller_setup.hpp"
#include "comply/transport/cdr.hpp"
#include "unit/ws_test_client.hpp"

namespace comply::host {
namespace {

using namespace std::chrono_literals;

std::shared_ptr<const pipeline::ResolvedController> fr3() {
  return pipeline::resolveController(simControllerConfig("fr3", "cartesian_impedance", ""));
}

TEST(ViewAddress, PortAloneOrWithAnAddress) {
  EXPECT_EQ(parseViewAddress("8765").address, "127.0.0.1");
  EXPECT_EQ(parseViewAddress("8765").port, 8765);
  const LiveViewOptions all = parseViewAddress("0.0.0.0:9000");
  EXPECT_EQ(all.address, "0.0.0.0");
  EXPECT_EQ(all.port, 9000);
  EXPECT_EQ(parseViewAddress("[::1]:0").address, "::1");
  for (const char* bad : {"", "x", "70000", ":80", "1.2.3.4:", "1.2.3.4:-1"}) {
    EXPECT_THROW(parseViewAddress(bad), std::invalid_argument) << bad;
  }
}

TEST(LiveView, TheControlThreadsSideAllocatesNothingWithOrWithoutAViewer) {
  LiveViewOptions options;
  options.port = 0;
  LiveView view(options, fr3(), "comply");
  StateSample sample;
  sample.joints = JointState::zero(7);
  const auto in_force =
      std::get<comply_cartesian_command>(pipeline::emptyBus(COMPLY_COMMAND_CARTESIAN));
  comply::testing::AllocationCounter counter;
  counter.start();
  for (int i = 0; i < 1000; ++i) {
    view.cycle<CartesianCommand>(sample, in_force, 1e-5, 0.0);
  }
  EXPECT_EQ(counter.stop(), 0U);
  EXPECT_FALSE(view.viewing());

  const std::uint16_t port =
      static_cast<std::uint16_t>(std::stoi(view.url().substr(view.url().rfind(':') + 1)));
  viewer::testing::WsTestClient client(port, "foxglove.sdk.v1");
  client.readJson();
  const auto advertise = client.readJson();
  int state_channel = -1;
  std::vector<std::string> topics;
  for (const auto& channel : advertise["channels"]) {
    topics.push_back(channel["topic"]);
    if (channel["topic"] == "/comply/state") {
      state_channel = channel["id"];
    }
  }
  for (const char* topic : {"/comply/state", "/comply/cycle", "/comply/diagnostics",
                            "/comply/outcome", "/comply/cartesian_command", "/comply/joint_command",
                            "/comply/cartesian_chunk", "/comply/joint_chunk", "/comply/request"}) {
    EXPECT_NE(std::find(topics.begin(), topics.end(), topic), topics.end()) << topic;
  }
  ASSERT_GE(state_channel, 0);
  client.subscribe(0, static_cast<std::uint32_t>(state_channel));
  ASSERT_TRUE(view.waitForViewer(5.0));
  for (int i = 0; i < 400 && !view.viewing(); ++i) {
    std::this_thread::sleep_for(5ms);
  }
  ASSERT_TRUE(view.viewing());
  std::this_thread::sleep_for(50ms);  // the subscription taken
  sample.cycle = 4242;
  sample.wall = transport::Stamp::fromNanoseconds(1'700'000'000'123'456'789);
  sample.joints.position[3] = -1.25;
  counter.start();
  for (int i = 0; i < 1000; ++i) {
    view.cycle<CartesianCommand>(sample, in_force, 1e-5, 0.0);
  }
  EXPECT_EQ(counter.stop(), 0U) << "with a viewer connected";
  for (;;) {
    const viewer::testing::WsMessage message = client.read();
    if (message.text) {
      continue;
    }
    const std::string payload = message.payload();
    transport::ControllerStateMessage state;
    ASSERT_TRUE(transport::decodeCdr(
        std::span(reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size()), state));
    EXPECT_EQ(state.cycle, 4242U);
    EXPECT_EQ(state.position.at(3), -1.25);
    EXPECT_EQ(message.logTime(), 1'700'000'000'123'456'789U);
    break;
  }
}

}  // namespace
}  // namespace comply::host
