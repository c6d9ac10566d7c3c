// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer harness of the .bpt reader (Core/BptReader): the bytes are a .bpt file, parsed from
// a stream. A parsed file's patches are evaluated once each (the reader promises valid degrees
// and finite control points). The only exception allowed out of the reader is InputError;
// anything else (another exception, a sanitizer report, a hang, an allocation beyond the limit)
// is a finding. With SPHCOVER_FUZZ_INVARIANTS=1, an accepted file must also be text: a NUL
// byte is neither whitespace nor part of a C number (off by default while that finding is open;
// Testing/Data/bad/fuzz/README.md).
#include "scene/BptReader.h"
#include "scene/InputError.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>

namespace
{
const bool Invariants = []
{
  const char* value = std::getenv("SPHCOVER_FUZZ_INVARIANTS");
  return value && std::string(value) == "1";
}();
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try
  {
    const std::vector<sphcover::BezierPatch> patches = sphcover::ParseBpt(in, "fuzz.bpt");
    if (patches.empty())
    {
      std::abort(); // the reader promises at least one patch
    }
    if (Invariants && std::memchr(data, 0, size))
    {
      std::abort(); // accepted a file with a NUL byte
    }
    for (const sphcover::BezierPatch& patch : patches)
    {
      (void)patch.Evaluate(0.5, 0.5);
    }
  }
  catch (const sphcover::InputError&)
  {
  }
  return 0;
}
