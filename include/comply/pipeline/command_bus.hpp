#pragma once
// Conversion between the C++ command types (core) and the plugin buses (abi.h): derived from the
// command schema tables, see schema/schema.hpp.

#include "comply/schema/schema.hpp"

namespace comply::pipeline {

using schema::toBus;

}  // namespace comply::pipeline
