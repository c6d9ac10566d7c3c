// SPDX-License-Identifier: BSD-3-Clause
#include "scene/BptReader.h"

#include "scene/InputError.h"
#include "scene/InputFile.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace sphcover
{
namespace
{

/// Whitespace-separated tokens with the line each starts on.
class TokenStream
{
public:
  TokenStream(std::istream& in, const std::string& name)
    : In(in)
    , Name(name)
  {
  }

  /// False at end of input.
  bool Next(std::string& token)
  {
    token.clear();
    int c = 0;
    while ((c = this->In.get()) != EOF && std::isspace(c))
    {
      if (c == '\n')
      {
        ++this->Line;
      }
    }
    if (c == EOF)
    {
      return false;
    }
    this->TokenLine = this->Line;
    while (c != EOF && !std::isspace(c))
    {
      if (c == '\0')
      {
        // strtod would stop at it and accept "1<NUL>garbage" as 1.
        this->Fail("NUL byte (a binary file, not a .bpt text file?)");
      }
      token.push_back(static_cast<char>(c));
      c = this->In.get();
    }
    if (c == '\n')
    {
      ++this->Line;
    }
    return true;
  }

  [[noreturn]] void Fail(const std::string& problem) const
  {
    throw InputError(this->Name, "line " + std::to_string(this->TokenLine), problem);
  }

  std::string Require(const char* what)
  {
    std::string token;
    if (!this->Next(token))
    {
      // Located at the last token read: the line where the data stops.
      this->Fail(std::string("unexpected end of file (expected ") + what + ")");
    }
    return token;
  }

  long ReadInteger(const char* what)
  {
    const std::string token = this->Require(what);
    char* end = nullptr;
    errno = 0;
    const long value = std::strtol(token.c_str(), &end, 10);
    if (end == token.c_str() || *end != '\0' || errno == ERANGE)
    {
      this->Fail(std::string("expected an integer (") + what + "), got " + Quote(token));
    }
    return value;
  }

  /// A finite number of magnitude at most `limit`.
  double ReadNumber(const char* what, double limit)
  {
    const std::string token = this->Require(what);
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0')
    {
      this->Fail(std::string("expected a number (") + what + "), got " + Quote(token));
    }
    // A value below the normal range (1e-310) or underflowing to 0 (1e-400) is harmless: it is
    // read as strtod rounds it, as in a scene file.
    if (!std::isfinite(value))
    {
      this->Fail(std::string("not a finite number (") + what + "): " + Quote(token));
    }
    if (std::fabs(value) > limit)
    {
      std::ostringstream problem;
      problem << what << " too large: " << Quote(token) << " (the limit is " << limit
              << " in magnitude)";
      this->Fail(problem.str());
    }
    return value;
  }

private:
  std::istream& In;
  const std::string& Name;
  int Line = 1;
  int TokenLine = 1;
};

} // namespace

std::vector<BezierPatch> ParseBpt(std::istream& in, const std::string& displayName)
{
  TokenStream tokens(in, displayName);
  const long count = tokens.ReadInteger("patch count");
  if (count < 1)
  {
    tokens.Fail("patch count must be a positive integer, got " + std::to_string(count));
  }
  std::vector<BezierPatch> patches;
  for (long p = 0; p < count; ++p)
  {
    const std::string which = " of patch " + std::to_string(p + 1) + " of " + std::to_string(count);
    const long du = tokens.ReadInteger("u degree");
    const long dv = tokens.ReadInteger("v degree");
    if (du < 1 || du > BezierPatch::MaxDegree || dv < 1 || dv > BezierPatch::MaxDegree)
    {
      tokens.Fail("degree must be in [1, " + std::to_string(BezierPatch::MaxDegree) + "], got " +
        std::to_string(du) + " " + std::to_string(dv) + which);
    }
    std::vector<glm::dvec3> points(static_cast<size_t>((du + 1) * (dv + 1)));
    for (auto& point : points)
    {
      for (int k = 0; k < 3; ++k)
      {
        point[k] = tokens.ReadNumber("control point coordinate", BezierPatch::MaxCoordinate);
      }
    }
    patches.emplace_back(static_cast<int>(du), static_cast<int>(dv), std::move(points));
  }
  std::string extra;
  if (tokens.Next(extra))
  {
    tokens.Fail("unexpected data after the last patch: " + Quote(extra));
  }
  return patches;
}

std::vector<BezierPatch> ReadBptFile(const std::string& path)
{
  std::ifstream in = OpenInputFile(path);
  return ParseBpt(in, path);
}

} // namespace sphcover
