// SPDX-License-Identifier: BSD-3-Clause
#include "scene/InputFile.h"

#include "scene/InputError.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>

namespace sphcover
{

std::string LowerExtension(const std::string& path)
{
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return std::string();
  }
  std::string ext = path.substr(dot + 1);
  std::transform(
    ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::uintmax_t CheckInputFile(const std::string& path)
{
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (status.type() == fs::file_type::not_found || status.type() == fs::file_type::none)
  {
    throw InputError(path, "", "cannot open file");
  }
  if (status.type() == fs::file_type::directory)
  {
    throw InputError(path, "", "is a directory, not a file");
  }
  if (status.type() != fs::file_type::regular)
  {
    // Named by kind, so that "why does it refuse /dev/stdin?" answers itself.
    const char* kind = status.type() == fs::file_type::fifo ? "a FIFO"
      : status.type() == fs::file_type::character || status.type() == fs::file_type::block
      ? "a device"
      : status.type() == fs::file_type::socket ? "a socket"
                                               : "not a file";
    throw InputError(path, "", std::string("not a regular file (") + kind + ")");
  }
  const std::uintmax_t size = fs::file_size(path, error);
  if (error)
  {
    throw InputError(path, "", "cannot open file");
  }
  if (size > MaxInputFileBytes)
  {
    throw InputError(path,
      "",
      "file too large (" + std::to_string(size) + " bytes; the limit is " +
        std::to_string(MaxInputFileBytes >> 20) + " MiB)");
  }
  return size;
}

std::ifstream OpenInputFile(const std::string& path)
{
  CheckInputFile(path);
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throw InputError(path, "", "cannot open file");
  }
  return in;
}

std::string ReadInputFile(const std::string& path)
{
  std::ifstream in = OpenInputFile(path);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad())
  {
    throw InputError(path, "", "cannot read file");
  }
  return text.str();
}

} // namespace sphcover
