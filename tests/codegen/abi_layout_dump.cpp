// Prints the structs of abi.h from abi_layout.hpp in print_buses.m's format; the struct sizes come
// from sizeof on abi.h itself.
#include <cstdio>

#include "comply/plugin/abi_layout.hpp"

int main() {
  using namespace comply::plugin::abi_layout;
  const char* names[] = {"double", "int32", "uint32", "int8"};
  for (const auto& bus : kStructs) {
    for (const auto& e : bus.elements) {
      std::printf("%s %s %zu %s %zu\n", bus.name.data(), e.name.data(), e.count,
                  names[static_cast<int>(e.type)], e.offset);
    }
    std::printf("%s sizeof %zu\n", bus.name.data(), bus.size);
  }
  return 0;
}
