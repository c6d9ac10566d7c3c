// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file InputFile.h
 * @brief The one policy for opening input files (scenes, .bpt, BRDF tables, meshes): only a
 * regular file of at most MaxInputFileBytes is read.
 *
 * Checked with stat before anything opens the file, because opening is itself the danger: a
 * FIFO blocks open() until a writer appears, and /dev/zero or /dev/urandom never end, so a
 * reader that streams them grows without bound. A directory opens fine on Linux and then reads
 * as an empty file, which would be reported as a misleading "unexpected end of file". Every
 * reader of user input, and every path handed to a VTK reader, goes through CheckInputFile.
 */
#ifndef SPHCOVER_INPUTFILE_H
#define SPHCOVER_INPUTFILE_H

#include <cstdint>
#include <fstream>
#include <string>

namespace sphcover
{

/// 64 MiB: a thousand times the largest file in Data/, and small enough that the readers'
/// memory (a JSON document tree is about ten times its text) stays well under a gigabyte.
constexpr std::uintmax_t MaxInputFileBytes = std::uintmax_t(64) << 20;

/// The extension of the file name in `path`, lower case, without the dot ("" if none).
std::string LowerExtension(const std::string& path);

/// Returns the size of `path` in bytes. Throws InputError(path, "", problem) unless it is a
/// regular file (after following symbolic links) of at most MaxInputFileBytes: "cannot open
/// file" (it does not exist), "is a directory", "not a regular file (...)", "file too large".
std::uintmax_t CheckInputFile(const std::string& path);

/// CheckInputFile, then opens the file for binary reading ("cannot open file" if that fails).
std::ifstream OpenInputFile(const std::string& path);

/// CheckInputFile, then the whole content of the file.
std::string ReadInputFile(const std::string& path);

} // namespace sphcover

#endif
