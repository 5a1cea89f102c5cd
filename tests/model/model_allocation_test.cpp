// The update is on the real-time path: 10,000 updates of every quantity must not allocate.

#include <gtest/gtest.h>

#include "allocation_counter.hpp"
#include "comply/model/robot_description.hpp"
#include "comply/model/update.hpp"
#include "robot_sampling.hpp"

namespace comply::model {
namespace {

constexpr int kUpdates = 10000;

class AllocationTest : public ::testing::TestWithParam<std::string> {};

TEST_P(AllocationTest, UpdatesDoNotAllocate) {
  const RobotDescription robot = loadRobotDescription(GetParam());
  const Model model = robot.loadModel();
  Data data(model);
  data.payload = {0.8, Eigen::Vector3d(0.0, 0.0, 0.05)};
  testing::JointSampler sampler(model, 3);
  std::vector<testing::JointSample> samples;
  for (int i = 0; i < 100; ++i) {
    samples.push_back(sampler.next());
  }

  testing::AllocationCounter counter;
  counter.start();
  int failures = 0;
  for (int i = 0; i < kUpdates; ++i) {
    const testing::JointSample& sample = samples[i % samples.size()];
    failures += update(model, data, sample.q, sample.dq, Quantity::kAll) != UpdateStatus::kOk;
  }
  const std::size_t allocations = counter.stop();
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(allocations, 0U) << GetParam() << ": " << allocations << " allocations in " << kUpdates
                             << " updates";

  // The counter itself must see an allocation, or the zero above proves nothing.
  counter.start();
  auto* probe = new std::vector<double>(16);
  asm volatile("" : : "g"(probe) : "memory");  // keep the compiler from eliding the pair
  delete probe;
  EXPECT_GE(counter.stop(), 1U);
}

INSTANTIATE_TEST_SUITE_P(Robots, AllocationTest, ::testing::ValuesIn(testing::shippedRobots()),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace
}  // namespace comply::model
