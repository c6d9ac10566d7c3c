// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file OutputFiles.h
 * @brief Output files that appear whole or not at all: no run of sphcover, failed, interrupted or
 * killed, leaves a half-written output or replaces an existing one with a broken file.
 *
 * Every output is written into a hidden staging folder beside its target,
 * `.<name>.sphcover-<pid>.<random>`, and renamed into place when complete (a multiblock file's
 * folder of pieces first, the file that refers to them last). The staging folder is removed
 *  - when the write fails (the error names the target);
 *  - when the process ends before the write is complete, by any cause (SIGINT, SIGTERM, a crash,
 *    SIGKILL of sphcover alone): by a janitor process that waits for sphcover to end;
 *  - when the janitor was killed too (SIGKILL of the whole process group), by the next run that
 *    writes into the same folder (the pid in the name no longer runs).
 * SIGINT, SIGTERM and SIGHUP print "sphcover: interrupted" and end the process by the signal,
 * never in the middle of the renames into place.
 */
#ifndef SPHCOVER_OUTPUTFILES_H
#define SPHCOVER_OUTPUTFILES_H

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

class vtkDataObject;
class vtkImageData;
class vtkMultiProcessController;
class vtkXMLWriter;

namespace sphcover_cli
{
/// Lower-case extension of a path, with its dot ("" if none).
std::string ExtensionOf(const std::string& path);

/**
 * Checks an output path before any work starts (a solve can take minutes; failing to write
 * afterwards wastes it): one of `extensions`, not a folder, in an existing folder this process
 * may write to. An empty path (the option not given) passes. Throws one line naming the option.
 */
void CheckOutputPath(const std::string& option,
  const std::string& path,
  const std::vector<std::string>& extensions,
  const std::string& kind);

/// Starts the janitor process, blocks SIGINT, SIGTERM and SIGHUP and starts the thread that
/// handles them. Call it in main() before any other thread exists: the janitor is forked, and
/// every thread must inherit the blocked mask.
void WatchTerminationSignals();

/// Writes `path` whole: `write` writes the output at the path it is given (inside the staging
/// folder; it may create a folder of pieces named after the file's stem there). Throws
/// std::runtime_error("cannot write '<path>': ...") on failure, leaving no trace.
void WriteAtomically(const std::string& path,
  const std::function<void(const std::filesystem::path&)>& write);

/// A dataset through a VTK XML writer (data inline, see the .cxx for why).
void WriteXmlAtomically(vtkXMLWriter* writer, vtkDataObject* data, const std::string& path);

/// The same written together by the ranks of `controller` through a parallel XML writer (each
/// rank writes its own pieces, rank 0 the file that refers to them): rank 0 stages the output
/// and moves it into place once every rank has written its part. Collective: every rank throws
/// on failure, rank 0 with the reason.
void WriteXmlAtomicallyOnRanks(vtkXMLWriter* writer,
  vtkDataObject* data,
  const std::string& path,
  vtkMultiProcessController* controller);

/// Text, such as the JSON report.
void WriteTextAtomically(const std::string& text, const std::string& path);

/// The image's `RGB` array as PNG.
void WritePngAtomically(vtkImageData* image, const std::string& path);

/// The image's HDR `Radiance` (float RGB, channels R, G, B) and `Depth` as OpenEXR (channel
/// `Z`, +infinity where no surface is seen: vtkOpenEXRWriter.h).
void WriteExrAtomically(vtkImageData* image, const std::string& path);
}

#endif
