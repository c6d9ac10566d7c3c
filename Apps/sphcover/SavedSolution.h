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
#include <vtkSmartPointer.h>
#include <vtkXMLMultiBlockDataReader.h>

#include <string>

class ErrorCollector;
class vtkDataObject;
class vtkMultiProcessController;

namespace sphcover_cli
{
struct Options;

struct SavedSolution
{
  vtkNew<vtkXMLMultiBlockDataReader> Reader;
  /// A solution written in pieces joined (vtkSolutionPieces), or this rank's piece
  /// (ReadPiece), else unused.
  vtkNew<vtkPolyData> Joined;
  /// What ReadPiece read.
  vtkSmartPointer<vtkDataObject> PiecePatches;
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

  /**
   * Under mpiexec, a solution written in as many pieces as there are ranks (`controller`'s):
   * every rank reads the patches, the illumination and its own share of the cover, and
   * Illumination is its piece (vtkSolutionPieces::Merge), for rendering by the ranks together
   * (vtkRankRenderer). Collective then: `problem` (what the caller found before, "" if nothing)
   * and what the reading finds are agreed, and every rank throws the first. False, with
   * nothing read and no communication, when the file is not in that many pieces (every rank
   * parses the same file alike).
   */
  bool ReadPiece(const Options& options,
    vtkMultiProcessController* controller,
    const std::string& problem);

  /// Throws one line unless the illumination carries the fingerprint of `scene` (the reader's
  /// output of options.Scene).
  void CheckFingerprint(const Options& options, vtkDataObject* scene) const;
};
}

#endif
