// The library's reader of the VTU files fibra writes (io/vtu_reader.h), under the tests' names.
#pragma once

#include "io/vtu_reader.h"

namespace fibra::test {

using fibra::readVtuArrays;
using fibra::VtuArrays;

}  // namespace fibra::test
