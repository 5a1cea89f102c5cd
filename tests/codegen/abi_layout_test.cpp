// abi_layout.hpp against abi.h: offsets and sizes come from the compiler, so what can go wrong is a
// member missing from the table or listed out of order. Requiring each element to start where the
// previous one ends (rounded up to its own alignment) and the last to end the struct rules out
// both.
#include "comply/plugin/abi_layout.hpp"

#include <gtest/gtest.h>

namespace comply::plugin::abi_layout {
namespace {

std::size_t alignUp(std::size_t value, std::size_t alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

TEST(AbiLayout, ElementsTileEveryStruct) {
  for (const auto& bus : kStructs) {
    std::size_t end = 0;
    for (const auto& element : bus.elements) {
      const std::size_t scalar = scalarSize(element.type);
      EXPECT_EQ(element.offset, alignUp(end, scalar)) << bus.name << "." << element.name;
      EXPECT_EQ(element.size, element.count * scalar) << bus.name << "." << element.name;
      end = element.offset + element.size;
    }
    EXPECT_EQ(bus.size, alignUp(end, bus.alignment)) << bus.name;
  }
}

TEST(AbiLayout, KnownShapes) {
  EXPECT_EQ(kStructs[0].name, "comply_input");
  EXPECT_EQ(kInputElements.size(), 13u);
  EXPECT_EQ(kInputElements[9].name, "jacobian");
  EXPECT_EQ(kInputElements[9].count, 6u * COMPLY_MAX_DOF);
  EXPECT_EQ(kCartesianCommandElements[11].type, ScalarType::kInt32);  // damping_mode
  EXPECT_EQ(kOutputElements[1].count, std::size_t{COMPLY_MESSAGE_CAPACITY});
  EXPECT_EQ(kOutputElements[1].type, ScalarType::kChar);
}

}  // namespace
}  // namespace comply::plugin::abi_layout
