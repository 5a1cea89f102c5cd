# Warning and optimisation flags shared by every comply target.
add_library(comply_flags INTERFACE)
# Exported only because static libraries of the package name it as a link-only dependency.
set_target_properties(comply_flags PROPERTIES EXPORT_NAME flags)
install(TARGETS comply_flags EXPORT complyTargets)
target_compile_options(comply_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  # Flowing off the end of a function that returns a value is undefined behaviour the optimiser
  # exploits (a crash far from the cause): never a warning to live with.
  -Werror=return-type
  $<$<COMPILE_LANGUAGE:CXX>:-Wnon-virtual-dtor>)
# GCC 12 reports false -Wrestrict positives inside std::string concatenation (GCC bug 105329).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(comply_flags INTERFACE $<$<COMPILE_LANGUAGE:CXX>:-Wno-restrict>)
  # With AVX-512 enabled, GCC 12 flags the deliberately undefined `__Y = __Y` inside its own
  # intrinsic headers as maybe-uninitialized when Eigen reduces a vector (GCC bug 105593).
  target_compile_options(comply_flags INTERFACE -Wno-maybe-uninitialized)
endif()
# Global, not per target: Eigen's fixed-size types change alignment with the instruction set, so
# every translation unit that shares a struct holding them must be compiled with the same flags.
if(COMPLY_NATIVE)
  add_compile_options(-march=native)
endif()

# COMPLY_SANITIZE: sanitizers for the whole build (make test-asan: "address;undefined", make
# test-tsan: "thread"), each in its own build folder. Debug information for the reports, no
# optimisation that would hide a finding behind inlining.
set(COMPLY_SANITIZE "" CACHE STRING "sanitizers: address;undefined, or thread (empty: none)")
if(COMPLY_SANITIZE)
  list(JOIN COMPLY_SANITIZE "," sanitizers)
  add_compile_options(-fsanitize=${sanitizers} -fno-omit-frame-pointer -g
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=${sanitizers})
endif()
