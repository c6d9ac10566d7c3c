// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file InputError.h
 * @brief The one error type for bad input files: names the file, the location and the problem.
 *
 * Every reader of user input (scene JSON, .bpt, meshes) reports problems by throwing an
 * InputError; its what() is the single line shown to the user,
 * `<file>: <location>: <problem>`, where the location is `line L`, `line L, column C` or an
 * RFC 6901 JSON pointer such as `/surfaces/2/points/1`. The line is always printable: control
 * characters from the input (a NUL byte, a line break in a name) are written as escapes, and a
 * piece of the input quoted in a problem is cut short (Quote), however large the input.
 */
#ifndef SPHCOVER_INPUTERROR_H
#define SPHCOVER_INPUTERROR_H

#include <cstdio>
#include <stdexcept>
#include <string>

namespace sphcover
{

/// `text` with every control character written as an escape (\n, \r, \t, \xHH): a message
/// stays one line, and a NUL byte cannot end it early when it is printed as a C string. The
/// result has no control characters, so escaping a message twice changes nothing.
inline std::string Printable(const std::string& text)
{
  std::string out;
  out.reserve(text.size());
  for (const char c : text)
  {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte != 0x7f)
    {
      out += c;
    }
    else if (c == '\n')
    {
      out += "\\n";
    }
    else if (c == '\r')
    {
      out += "\\r";
    }
    else if (c == '\t')
    {
      out += "\\t";
    }
    else
    {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02x", byte);
      out += hex;
    }
  }
  return out;
}

/// The printable start of `text`, at most `keep` bytes (not splitting a UTF-8 character),
/// between `quote`s, followed by "... (N bytes)" when it was cut: a 1 MB token or key gives a
/// short message.
inline std::string Excerpt(const std::string& text, const char* quote = "", size_t keep = 60)
{
  size_t length = text.size();
  if (length > keep)
  {
    length = keep;
    while (length > 0 && (static_cast<unsigned char>(text[length]) & 0xc0) == 0x80)
    {
      --length; // text[length] continues a UTF-8 character: cut before that character
    }
  }
  const std::string rest =
    length < text.size() ? "... (" + std::to_string(text.size()) + " bytes)" : "";
  return quote + Printable(text.substr(0, length)) + quote + rest;
}

/// A piece of the input quoted in a problem: 'text', or 'start'... (N bytes) when it is long.
inline std::string Quote(const std::string& text, size_t keep = 60)
{
  return Excerpt(text, "'", keep);
}

class InputError : public std::runtime_error
{
public:
  InputError(const std::string& file, const std::string& location, const std::string& problem)
    : std::runtime_error(Format(file, location, problem))
    , File(file)
    , Location(location)
    , Problem(problem)
  {
  }

  const std::string File;
  const std::string Location;
  const std::string Problem;

private:
  static std::string Format(const std::string& file,
    const std::string& location,
    const std::string& problem)
  {
    return location.empty() ? Printable(file + ": " + problem)
                            : Printable(file + ": " + location + ": " + problem);
  }
};

} // namespace sphcover

#endif
