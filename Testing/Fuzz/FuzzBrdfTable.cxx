// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer harness of the BRDF table reader (Core/BrdfTable): the bytes are a .brdf.csv file,
// parsed from a stream. A parsed table is evaluated at a few directions (inside, on and beyond
// its grid) and its albedo computed on a coarse rule, so the interpolation runs on whatever
// grids the parser accepts. Only InputError may leave the reader; anything else (another
// exception, a sanitizer report, a hang, an allocation beyond the limit) is a finding.
#include "scene/BrdfTable.h"
#include "scene/InputError.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try
  {
    const sphcover::BrdfTable table = sphcover::BrdfTable::Parse(in, "fuzz.brdf.csv");
    const double angles[] = { 0.0, 0.3, M_PI / 4, M_PI / 2, 2.0, -1.0 };
    for (double a : angles)
    {
      for (double b : angles)
      {
        const glm::dvec3 f = table.Evaluate(std::fabs(a), std::fabs(b), a - b);
        if (!(f.x >= 0 && f.y >= 0 && f.z >= 0))
        {
          std::abort(); // the parser refuses negative values; interpolation cannot make one
        }
      }
    }
    (void)table.Albedo(0.5, 6, 12);
  }
  catch (const sphcover::InputError&)
  {
  }
  return 0;
}
