// The allocation counter must see every kind of heap allocation, including those made inside
// shared libraries, and nothing else; otherwise a "0 allocations" result proves nothing.

#include "allocation_counter.hpp"

#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdint>
#include <cstdlib>
#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/jntspaceinertiamatrix.hpp>
#include <memory>
#include <new>
#include <string>
#include <thread>
#include <vector>

namespace comply::testing {
namespace {

/// Hides a pointer from the optimiser, which may otherwise elide a new/delete or malloc/free pair.
template <typename T>
void escape(T* pointer) {
  asm volatile("" : : "g"(pointer) : "memory");
}

TEST(AllocationCounter, CountsOperatorNew) {
  AllocationCounter counter;
  counter.start();
  int* value = new int(3);
  escape(value);
  delete value;
  EXPECT_GE(counter.stop(), 1U);

  counter.start();
  int* values = new int[8];
  escape(values);
  delete[] values;
  EXPECT_GE(counter.stop(), 1U);

  struct alignas(64) Aligned {
    double x[8];
  };
  counter.start();
  auto* aligned = new Aligned;
  escape(aligned);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(aligned) % 64, 0U);
  delete aligned;
  EXPECT_GE(counter.stop(), 1U);

  counter.start();
  int* nothrow = new (std::nothrow) int(4);
  escape(nothrow);
  delete nothrow;
  EXPECT_GE(counter.stop(), 1U);
}

TEST(AllocationCounter, CountsStandardContainers) {
  AllocationCounter counter;
  counter.start();
  {
    std::vector<double> values(10);
    escape(values.data());
  }
  EXPECT_GE(counter.stop(), 1U);

  counter.start();
  {
    std::string text(100, 'x');  // longer than the small-string buffer
    escape(text.data());
  }
  EXPECT_GE(counter.stop(), 1U);
}

TEST(AllocationCounter, CountsCAllocationFunctions) {
  AllocationCounter counter;
  counter.start();
  void* block = std::malloc(32);
  escape(block);
  std::free(block);
  EXPECT_GE(counter.stop(), 1U);

  counter.start();
  block = std::calloc(4, 8);
  escape(block);
  std::free(block);
  EXPECT_GE(counter.stop(), 1U);

  block = std::malloc(8);
  counter.start();
  block = std::realloc(block, 4096);
  escape(block);
  EXPECT_GE(counter.stop(), 1U);
  std::free(block);

  counter.start();
  block = std::aligned_alloc(64, 128);
  escape(block);
  std::free(block);
  EXPECT_GE(counter.stop(), 1U);

  counter.start();
  ASSERT_EQ(posix_memalign(&block, 64, 128), 0);
  escape(block);
  std::free(block);
  EXPECT_GE(counter.stop(), 1U);

  counter.start();
  block = memalign(32, 64);
  escape(block);
  std::free(block);
  EXPECT_GE(counter.stop(), 1U);
}

TEST(AllocationCounter, FreeAndArithmeticAreNotCounted) {
  AllocationCounter counter;
  void* block = std::malloc(16);
  escape(block);
  auto* value = new double(1.0);
  escape(value);
  counter.start();
  volatile double x = 1.5;
  for (int i = 0; i < 100; ++i) {
    x = x * 1.0001 + 0.5;
  }
  std::free(block);
  delete value;
  EXPECT_EQ(counter.stop(), 0U);
}

TEST(AllocationCounter, CountsOnlyBetweenStartAndStop) {
  AllocationCounter counter;
  counter.start();
  EXPECT_EQ(counter.stop(), 0U);
  auto* outside = new int(1);
  escape(outside);
  counter.start();
  EXPECT_EQ(counter.stop(), 0U);
  delete outside;
}

TEST(AllocationCounter, IgnoresOtherThreads) {
  std::size_t in_thread = 0;
  // Constructing the thread allocates its state on this thread, so count only from here on.
  std::thread worker([&in_thread] {
    AllocationCounter own;
    own.start();
    auto* value = new int(2);
    escape(value);
    delete value;
    in_thread = own.stop();
  });
  AllocationCounter counter;
  counter.start();
  worker.join();
  EXPECT_EQ(counter.stop(), 0U);  // the worker's allocation is not this thread's
  EXPECT_GE(in_thread, 1U);
}

/// Three revolute segments with some mass: enough for KDL's composite rigid-body algorithm to
/// touch all of its work arrays.
KDL::Chain threeLinkChain() {
  KDL::Chain chain;
  const KDL::RigidBodyInertia inertia(1.5, KDL::Vector(0.2, 0.0, 0.01),
                                      KDL::RotationalInertia(0.01, 0.02, 0.03));
  chain.addSegment(KDL::Segment("a", KDL::Joint("j1", KDL::Joint::RotZ),
                                KDL::Frame(KDL::Vector(0.0, 0.0, 0.3)), inertia));
  chain.addSegment(KDL::Segment("b", KDL::Joint("j2", KDL::Joint::RotY),
                                KDL::Frame(KDL::Vector(0.4, 0.0, 0.0)), inertia));
  chain.addSegment(KDL::Segment("c", KDL::Joint("j3", KDL::Joint::RotY),
                                KDL::Frame(KDL::Vector(0.3, 0.0, 0.0)), inertia));
  return chain;
}

TEST(AllocationCounter, SeesAllocationsInsideSharedLibraries) {
  // KDL::JntArray's constructor allocates its Eigen vector inside liborocos-kdl.so: the counter
  // must interpose allocations made by other modules, not only by this executable.
  AllocationCounter counter;
  counter.start();
  auto array = std::make_unique<KDL::JntArray>(7);
  const std::size_t count = counter.stop();
  EXPECT_GE(count, 1U);
  escape(array.get());
}

TEST(AllocationCounter, KdlMassMatrixDoesNotAllocateOnceSetUp) {
  const KDL::Chain chain = threeLinkChain();
  KDL::ChainDynParam dynamics(chain, KDL::Vector(0.0, 0.0, -9.81));
  KDL::JntArray q(chain.getNrOfJoints());
  KDL::JntSpaceInertiaMatrix mass(chain.getNrOfJoints());
  q(0) = 0.3;
  q(1) = -0.7;
  q(2) = 1.1;

  AllocationCounter counter;
  counter.start();
  const int status = dynamics.JntToMass(q, mass);
  const std::size_t allocations = counter.stop();
  ASSERT_GE(status, 0);
  EXPECT_EQ(allocations, 0U);
  EXPECT_GT(mass(0, 0), 0.0);
}

}  // namespace
}  // namespace comply::testing
