// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file InputError.h
 * @brief The one error type for bad input files: names the file, the location and the problem.
 *
 * Every reader of user input (scene JSON, .bpt, meshes) reports problems by throwing an
 * InputError; its what() is the single line shown to the user,
 * `<file>: <location>: <problem>`, where the location is `line L`, `line L, column C` or an
 * RFC 6901 JSON pointer such as `/surfaces/2/points/1`.
 */
#ifndef SPHCOVER_INPUTERROR_H
#define SPHCOVER_INPUTERROR_H

#include <stdexcept>
#include <string>

namespace sphcover
{

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
    return location.empty() ? file + ": " + problem : file + ": " + location + ": " + problem;
  }
};

} // namespace sphcover

#endif
