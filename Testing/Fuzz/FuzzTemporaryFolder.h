// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FuzzTemporaryFolder.h
 * @brief A folder of the fuzzing process's own under $TMPDIR (or /tmp), made once and removed
 * at exit, for the harnesses that must give a reader a path.
 */
#ifndef SPHCOVER_FUZZTEMPORARYFOLDER_H
#define SPHCOVER_FUZZTEMPORARYFOLDER_H

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace FuzzTemporaryFolder
{
/// The folder (made on the first call; every call returns the same one).
inline const std::filesystem::path& Get()
{
  static const std::filesystem::path folder = []
  {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/sphcover-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data()))
    {
      std::perror("sphcover fuzz: mkdtemp");
      std::abort();
    }
    std::atexit(
      []
      {
        std::error_code ignored;
        std::filesystem::remove_all(Get(), ignored);
      });
    return std::filesystem::path(pattern);
  }();
  return folder;
}

/// Writes `size` bytes to `file` (replacing it), making its folders; aborts on failure (a
/// harness that cannot write its input would fuzz nothing).
inline void WriteBytes(const std::filesystem::path& file, const uint8_t* data, size_t size)
{
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out)
  {
    std::perror("sphcover fuzz: writing the input");
    std::abort();
  }
}

inline void WriteText(const std::filesystem::path& file, const std::string& text)
{
  WriteBytes(file, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}
}

#endif
