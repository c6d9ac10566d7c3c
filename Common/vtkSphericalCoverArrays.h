// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSphericalCoverArrays
 * @brief Stores a spherical cover (paper §3.3) in a dataset's field data and reads it back, so
 * a built cover survives VTK's XML writers and readers bit for bit.
 *
 * Field arrays (all raw numbers, no conversion): `CoverGrid` (int: ThetaBins, PhiBins,
 * SamplesTheta, SamplesPhi, Fill, UnoccludedKnown), `CoverRowOffsets` (uint64, N+1: row i's
 * entries), `CoverEntries` (uint32 x 2: source, first strip), `CoverUnoccluded` (float, per
 * entry), `CoverStrips` (uint16 x 3: theta row, phi begin, phi end), `CoverStripDepths`
 * (float, per strip). Patch areas are the point data `Area`. The columns are rebuilt on load.
 */
#ifndef vtkSphericalCoverArrays_h
#define vtkSphericalCoverArrays_h

#include "SphericalCoverCommonModule.h" // for export macro

#include <string>

class vtkDataObject;
class vtkDataSet;
#include "cover/SphericalCover.h" // for SphericalCover::Arrays

class SPHERICALCOVERCOMMON_EXPORT vtkSphericalCoverArrays
{
public:
  /// Adds the cover's arrays to `output`'s field data (its point data must hold `Area`).
  static void Store(const sphcover::SphericalCover& cover, vtkDataSet* output);
  /// The same from the cover's exported arrays (SphericalCover::ExportArrays), each let go
  /// once copied: a cover moved out (`std::move(cover).ExportArrays()`) is stored with at most
  /// one of its arrays held twice.
  static void Store(sphcover::SphericalCover::Arrays arrays, vtkDataSet* output);

  /// Reads the cover of `input`; returns what is missing or inconsistent ("" on success). A
  /// rank's share of a cover (field array `CoverRowShare`: vtkSphericalCoverFilter with
  /// GatherRows off, or a piece of vtkLightPropagationFilter's solution with GatherSolution off)
  /// holds only some rows: it is refused unless `share` accepts one.
  static std::string Load(vtkDataSet* input, sphcover::SphericalCover& cover, bool share = false);

  /// Whether `name` is one of the field arrays Store adds (nullptr: no).
  static bool IsCoverArray(const char* name);

  /// Marks `output`'s cover as rank `rank` of `ranks`' share of the rows (the field array
  /// `CoverRowShare`, replaced if there).
  static void MarkShare(vtkDataObject* output, int rank, int ranks);
  /// Whether `data` is marked as one rank's share (MarkShare): of the cover's rows, or a piece
  /// of a solution kept in pieces.
  static bool IsShare(vtkDataObject* data);
};

#endif
