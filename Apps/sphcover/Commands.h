// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Commands.h
 * @brief The subcommands of `sphcover` (README.md#command-line), one file each: they run the VTK
 * pipeline and print or write what it gives. Errors throw one line (main prints it); the return
 * value is the exit status.
 */
#ifndef SPHCOVER_COMMANDS_H
#define SPHCOVER_COMMANDS_H

namespace sphcover_cli
{
struct Options;

/// sphcover info: the scene's summary.
int RunInfo(const Options& options);

/// sphcover subdivide: patches and characteristic points (paper §4) as a .vtm file.
int RunSubdivide(const Options& options);

/// sphcover solve: the method up to equilibrium, the solution file and the report.
int RunSolve(const Options& options);

/// sphcover render: the whole pipeline (or a saved solution) and the image of paper §5.3.
int RunRender(const Options& options);

/// sphcover walk: a saved solution's images of paper §5.3 through every camera of a path.
int RunWalk(const Options& options);
}

#endif
