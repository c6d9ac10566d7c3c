// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SavedSolution.h
 * @brief A solution written by `sphcover solve -o` (.vtm: block 0 the patches, block 1 the
 * illumination), read back for `render --solution` and `walk`, and the check that it was solved
 * from the scene given: the scene fingerprint (sphcover::Fingerprint) that the reader puts in its
 * field data and every stage passes on must be the one the solution carries.
 */
#ifndef SPHCOVER_SAVEDSOLUTION_H
#define SPHCOVER_SAVEDSOLUTION_H

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLMultiBlockDataReader.h>

#include <string>

class ErrorCollector;
class vtkDataObject;

namespace sphcover_cli
{
struct Options;

struct SavedSolution
{
  vtkNew<vtkXMLMultiBlockDataReader> Reader;
  /// A solution written in pieces joined (vtkSolutionPieces), else unused.
  vtkNew<vtkPolyData> Joined;
  vtkDataObject* Patches = nullptr;
  vtkPolyData* Illumination = nullptr;
  double ReadSeconds = 0.0;
  /// The option that named the file, in messages ("--solution 'x': ..."); empty: the file alone
  /// ("'x': ...", the positional SOLUTION of `sphcover walk`).
  std::string Option = "--solution";

  /// Reads --solution (with the "read" progress bar); throws one line when it is missing or
  /// not a solution of `solve -o`. A solution written in pieces (a third block, CoverShares:
  /// `solve -o` under mpiexec) is joined into the whole one.
  void Read(const Options& options, ErrorCollector& errors);

  /// Throws one line unless the illumination carries the fingerprint of `scene` (the reader's
  /// output of options.Scene).
  void CheckFingerprint(const Options& options, vtkDataObject* scene) const;
};
}

#endif
