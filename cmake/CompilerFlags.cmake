# Warning and optimisation flags shared by every comply target.
add_library(comply_flags INTERFACE)
target_compile_options(comply_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion)
# GCC 12 reports false -Wrestrict positives inside std::string concatenation (GCC bug 105329).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(comply_flags INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-Wno-restrict>)
endif()
if(COMPLY_NATIVE)
  target_compile_options(comply_flags INTERFACE -march=native)
endif()
# Eigen's fixed-size types are over-aligned; C++17 aligned new handles that, so no EIGEN_MAKE_ALIGNED.
