// SPDX-License-Identifier: BSD-3-Clause
// vtkSphericalCoverFilter (Documentation/Pipeline.md#spherical-cover):
// - inside closed enclosures (the 8-patch Bezier sphere, subdivided; the box) every
//   characteristic point's CoveredProjectedSolidAngle is pi;
// - a built cover written with VTK's XML writer and read back is identical, array for array
//   and cell for cell;
// - the result does not depend on the number of threads;
// - the refinement splits patches across enclosure boundaries, keeping the total area, and
//   honours abort;
// - bad inputs, an empty grid and a memory limit below the estimate give one clear error.
#include "FailureExpectation.h"
#include "TestFailures.h"
#include "vtkIntervalSubdivisionFilter.h"
#include "vtkPSphericalCoverFilter.h"
#include "vtkPatchSceneReader.h"
#include "vtkSphericalCoverArrays.h"
#include "vtkSphericalCoverFilter.h"

#include "cover/SphericalCover.h"

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <utility>

namespace
{
using TestFailures::Check;

template<typename T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() &&
    (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool SameCover(const sphcover::SphericalCover& a, const sphcover::SphericalCover& b)
{
  const sphcover::SphericalCover::Arrays x = a.ExportArrays();
  const sphcover::SphericalCover::Arrays y = b.ExportArrays();
  bool same = x.ThetaBins == y.ThetaBins && x.PhiBins == y.PhiBins &&
    x.SamplesTheta == y.SamplesTheta && x.SamplesPhi == y.SamplesPhi && x.Fill == y.Fill &&
    x.UnoccludedKnown == y.UnoccludedKnown && SameBytes(x.RowOffsets, y.RowOffsets) &&
    SameBytes(x.Entries, y.Entries) && SameBytes(x.Unoccluded, y.Unoccluded) &&
    SameBytes(x.Strips, y.Strips) && SameBytes(x.StripDepths, y.StripDepths) &&
    SameBytes(x.Areas, y.Areas) && SameBytes(x.Measures, y.Measures);
  for (size_t i = 0; same && i < a.PatchCount(); ++i)
  {
    same = a.ExpandRow(i) == b.ExpandRow(i) && a.ColumnBegin(i) == b.ColumnBegin(i);
  }
  return same;
}
}

int TestSphericalCoverFilter(int, char*[])
{
  vtkNew<vtkPatchSceneReader> sphere;
  sphere->SetFileName(SPHCOVER_DATA_DIR "/scenes/furnace_sphere.scene");
  vtkNew<vtkIntervalSubdivisionFilter> subdivision;
  subdivision->SetInputConnection(sphere->GetOutputPort());
  subdivision->SetMaxLevel(2);

  // Closed enclosures: every hemisphere fully covered, with both fills, on the curved sphere
  // (its pieces split along different directions meet without cracks) and on the flat box.
  vtkNew<vtkPatchSceneReader> flatBox;
  flatBox->SetFileName(SPHCOVER_DATA_DIR "/scenes/furnace_box.scene");
  vtkNew<vtkIntervalSubdivisionFilter> flatPatches;
  flatPatches->SetInputConnection(flatBox->GetOutputPort());
  flatPatches->SetMaxLevel(2);
  const std::pair<vtkAlgorithm*, int> closed[] = { { subdivision,
                                                     vtkSphericalCoverFilter::PROJECTION },
    { subdivision, vtkSphericalCoverFilter::RAY_CASTING },
    { flatPatches, vtkSphericalCoverFilter::PROJECTION },
    { flatPatches, vtkSphericalCoverFilter::RAY_CASTING } };
  for (const auto& run : closed)
  {
    vtkNew<vtkSphericalCoverFilter> cover;
    cover->SetInputConnection(run.first->GetOutputPort(0));
    cover->SetFillMethod(run.second);
    cover->Update();
    vtkDataArray* covered =
      cover->GetOutput()->GetPointData()->GetArray("CoveredProjectedSolidAngle");
    double worst = 0.0;
    for (vtkIdType k = 0; k < covered->GetNumberOfTuples(); ++k)
    {
      worst = std::max(worst, std::fabs(covered->GetComponent(k, 0) - M_PI));
    }
    std::cout << "closed enclosure, fill " << run.second << ": " << covered->GetNumberOfTuples()
              << " points, max |covered - pi| = " << worst << "\n";
    Check(covered->GetNumberOfTuples() > 8 && worst < 1e-9,
      "closed enclosure: every hemisphere covers pi");
    // A white furnace emits alike everywhere: no lamp, no measured region.
    sphcover::SphericalCover furnace;
    Check(vtkSphericalCoverArrays::Load(cover->GetOutput(), furnace).empty() &&
        furnace.ExportArrays().Measures.empty(),
      "a furnace has no measured regions");
  }

  // The Cornell box, coarsely subdivided: round trip through the XML writer and reader.
  vtkNew<vtkPatchSceneReader> box;
  box->SetFileName(SPHCOVER_DATA_DIR "/scenes/cornell_box.scene");
  vtkNew<vtkIntervalSubdivisionFilter> boxPatches;
  boxPatches->SetInputConnection(box->GetOutputPort());
  boxPatches->SetMaxLevel(2);
  vtkNew<vtkSphericalCoverFilter> cover;
  cover->SetInputConnection(boxPatches->GetOutputPort(0));
  vtkSMPTools::SetBackend("STDThread");
  vtkSMPTools::Initialize(1);
  cover->Update();
  sphcover::SphericalCover built;
  Check(vtkSphericalCoverArrays::Load(cover->GetOutput(), built).empty(),
    "the cover loads from the output");
  Check(built.StripCount() > 0 &&
      static_cast<vtkIdType>(built.StripCount()) ==
        vtkTable::SafeDownCast(cover->GetOutputDataObject(1))->GetNumberOfRows(),
    "the strip table has one row per strip");
  {
    // Without the table (the command line's pipeline): the same cover, an empty table.
    vtkNew<vtkSphericalCoverFilter> withoutTable;
    withoutTable->SetInputConnection(boxPatches->GetOutputPort(0));
    withoutTable->GenerateStripTableOff();
    withoutTable->Update();
    sphcover::SphericalCover same;
    Check(vtkSphericalCoverArrays::Load(withoutTable->GetOutput(), same).empty() &&
        SameCover(built, same) &&
        vtkTable::SafeDownCast(withoutTable->GetOutputDataObject(1))->GetNumberOfRows() == 0 &&
        vtkTable::SafeDownCast(withoutTable->GetOutputDataObject(1))->GetNumberOfColumns() == 0,
      "GenerateStripTable off: the same cover and an empty strip table");
  }
  {
    // GatherRows off on one process: nothing to keep apart, the whole cover, no share marker.
    vtkNew<vtkPSphericalCoverFilter> notGathered;
    notGathered->SetInputConnection(boxPatches->GetOutputPort(0));
    notGathered->GatherRowsOff();
    notGathered->Update();
    sphcover::SphericalCover same;
    Check(vtkSphericalCoverArrays::Load(notGathered->GetOutput(), same).empty() &&
        SameCover(built, same) &&
        !notGathered->GetOutput()->GetFieldData()->GetArray("CoverRowShare"),
      "GatherRows off on one process: the whole cover, not a share");

    // A cover marked as one rank's share (CoverRowShare) is refused by every reader of a whole
    // cover, with the reason, and read only by one that takes a share (the propagation's ranks).
    vtkNew<vtkPolyData> marked;
    marked->ShallowCopy(notGathered->GetOutput());
    vtkNew<vtkFieldData> fd;
    fd->ShallowCopy(notGathered->GetOutput()->GetFieldData());
    vtkNew<vtkIntArray> rowShare;
    rowShare->SetName("CoverRowShare");
    rowShare->SetNumberOfComponents(2);
    rowShare->InsertNextTuple2(0, 2);
    fd->AddArray(rowShare);
    marked->SetFieldData(fd);
    sphcover::SphericalCover refusedShare;
    const std::string problem = vtkSphericalCoverArrays::Load(marked, refusedShare);
    std::cout << "a share read as a whole cover: " << problem << "\n";
    Check(problem.find("share") != std::string::npos &&
        problem.find("GatherRows") != std::string::npos && refusedShare.Empty(),
      "a share is refused where a whole cover is read, naming GatherRows");
    sphcover::SphericalCover takenShare;
    Check(vtkSphericalCoverArrays::Load(marked, takenShare, true).empty() &&
        SameCover(built, takenShare),
      "a share is read where one is taken");
  }

  const std::string file =
    std::string(SPHCOVER_BINARY_DIR) + "/Testing/Temporary/TestSphericalCoverFilter.vtp";
  vtkNew<vtkXMLPolyDataWriter> writer;
  // As sphcover writes: inline data (appended data does not read back under expat >= 2.6).
  writer->SetDataModeToBinary();
  writer->SetInputData(cover->GetOutput());
  writer->SetFileName(file.c_str());
  Check(writer->Write() == 1, "the cover writes");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  sphcover::SphericalCover reloaded;
  Check(vtkSphericalCoverArrays::Load(reader->GetOutput(), reloaded).empty(),
    "the written cover loads");
  Check(SameCover(built, reloaded), "the cover read back is identical");
  // The lamp's regions are measured on the lamp (MeasureLamps, on by default): the rows keep
  // their covered measure, and the lamp's regions change; off, the cells' measures.
  {
    const std::vector<float>& measures = built.ExportArrays().Measures;
    Check(measures.size() == built.EntryCount(), "the Cornell box's lamp regions are measured");
    vtkNew<vtkSphericalCoverFilter> cells;
    cells->SetInputConnection(boxPatches->GetOutputPort(0));
    cells->MeasureLampsOff();
    cells->Update();
    sphcover::SphericalCover counted;
    vtkSphericalCoverArrays::Load(cells->GetOutput(), counted);
    Check(counted.ExportArrays().Measures.empty() && counted.EntryCount() == built.EntryCount(),
      "MeasureLamps off: the same regions, measured in cells");
    double worstRow = 0.0;
    size_t changed = 0;
    for (size_t i = 0; i < built.PatchCount(); ++i)
    {
      double a = 0.0;
      double b = 0.0;
      for (size_t e = built.EntryBegin(i); e < built.EntryEnd(i); ++e)
      {
        a += built.ProjectedSolidAngle(e);
        b += counted.ProjectedSolidAngle(e);
        changed += std::fabs(built.ProjectedSolidAngle(e) - counted.ProjectedSolidAngle(e)) >
            1e-6 * counted.ProjectedSolidAngle(e)
          ? 1
          : 0;
      }
      worstRow = std::max(worstRow, std::fabs(a - b));
    }
    std::cout << "measured lamp regions: " << changed << " regions changed, worst row change "
              << worstRow << "\n";
    Check(worstRow < 1e-5 && changed > built.PatchCount() / 2,
      "measured lamp regions keep every row's covered measure");

    // A corrupt CoverMeasures is refused with one explanation, the cover left empty: a
    // negative or NaN measure, one of the wrong length, one of the wrong type.
    const auto refused = [&](vtkAbstractArray* replacement, const char* what)
    {
      vtkNew<vtkPolyData> copy;
      copy->ShallowCopy(cover->GetOutput());
      vtkNew<vtkFieldData> fd;
      fd->DeepCopy(cover->GetOutput()->GetFieldData());
      fd->RemoveArray("CoverMeasures");
      replacement->SetName("CoverMeasures");
      fd->AddArray(replacement);
      copy->SetFieldData(fd);
      sphcover::SphericalCover loaded;
      const std::string problem = vtkSphericalCoverArrays::Load(copy, loaded);
      std::cout << what << ": " << problem << "\n";
      Check(!problem.empty() && loaded.Empty(), what);
    };
    const vtkIdType entries = static_cast<vtkIdType>(measures.size());
    for (const float bad : { -1.0f, std::nanf("") })
    {
      vtkNew<vtkFloatArray> values;
      values->SetNumberOfTuples(entries);
      for (vtkIdType e = 0; e < entries; ++e)
      {
        values->SetValue(e, measures[static_cast<size_t>(e)]);
      }
      values->SetValue(entries / 2, bad);
      refused(values, "a negative or NaN measure is refused");
    }
    vtkNew<vtkFloatArray> shorter;
    shorter->SetNumberOfTuples(entries - 1);
    shorter->FillValue(0.0f);
    refused(shorter, "measures of the wrong length are refused");
    vtkNew<vtkDoubleArray> doubles;
    doubles->SetNumberOfTuples(entries);
    doubles->FillValue(0.0);
    refused(doubles, "measures of the wrong type are refused");
  }

  // Two threads build the same cover.
  vtkSMPTools::Initialize(2);
  cover->Modified();
  cover->Update();
  sphcover::SphericalCover threaded;
  vtkSphericalCoverArrays::Load(cover->GetOutput(), threaded);
  Check(SameCover(built, threaded), "the cover does not depend on the number of threads");

  // The refinement (the default: enclosure boundaries) splits the floor patches along the
  // blocks' footprints and the ceiling's around the light: more points, the same total area,
  // the pieces marked SplitReason 5 (R-buffer) within the level limit; off, one point per patch.
  {
    vtkNew<vtkSphericalCoverFilter> unrefined;
    unrefined->SetInputConnection(boxPatches->GetOutputPort(0));
    unrefined->SetRefinement(vtkSphericalCoverFilter::REFINEMENT_OFF);
    unrefined->Update();
    const vtkIdType patches = boxPatches->GetOutput()->GetNumberOfCells();
    vtkPolyData* refinedPoints = cover->GetOutput();
    Check(unrefined->GetOutput()->GetNumberOfPoints() == patches,
      "without refinement one point per patch");
    Check(refinedPoints->GetNumberOfPoints() > patches, "the refinement splits some patches");
    auto areaSum = [](vtkPolyData* points)
    {
      vtkDataArray* area = points->GetPointData()->GetArray("Area");
      double sum = 0.0;
      for (vtkIdType k = 0; k < area->GetNumberOfTuples(); ++k)
      {
        sum += area->GetComponent(k, 0);
      }
      return sum;
    };
    Check(std::fabs(areaSum(refinedPoints) / areaSum(unrefined->GetOutput()) - 1.0) < 1e-9,
      "the refined patches' areas add up to the patches'");
    vtkDataArray* reason = refinedPoints->GetPointData()->GetArray("SplitReason");
    vtkDataArray* level = refinedPoints->GetPointData()->GetArray("Level");
    vtkIdType pieces = 0;
    bool withinLimit = reason && level;
    for (vtkIdType k = 0; withinLimit && k < refinedPoints->GetNumberOfPoints(); ++k)
    {
      if (reason->GetComponent(k, 0) == 5)
      {
        ++pieces;
        withinLimit = level->GetComponent(k, 0) <= 2 + cover->GetRefinementLevels();
      }
    }
    std::cout << "refinement: " << patches << " patches -> " << refinedPoints->GetNumberOfPoints()
              << " points, " << pieces << " pieces\n";
    Check(withinLimit && pieces > 0, "the pieces are marked and within the level limit");

    // Abort during the refinement: no output, no crash.
    vtkNew<vtkSphericalCoverFilter> aborted;
    aborted->SetInputConnection(boxPatches->GetOutputPort(0));
    vtkNew<vtkCallbackCommand> abort;
    abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
      { static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1); });
    aborted->AddObserver(vtkCommand::ProgressEvent, abort);
    aborted->Update();
    Check(aborted->GetOutput()->GetNumberOfPoints() == 0, "an aborted cover has no output");
  }

  // Bad inputs and limits.
  vtkNew<vtkSphericalCoverFilter> refused;
  refused->SetInputConnection(boxPatches->GetOutputPort(0));
  refused->SetMemoryLimit(0.001);
  TestFailures::Add(
    FailureExpectation::Check(refused, { "MemoryLimit" }, "a memory limit below the estimate"));
  // A grid whose R-buffers alone (4096 x 16384 cells, 9 samples each, per thread) exceed the
  // default MemoryLimit: refused from the options, before anything is allocated.
  vtkNew<vtkSphericalCoverFilter> oversized;
  oversized->SetInputConnection(boxPatches->GetOutputPort(0));
  oversized->SetThetaBins(4096);
  oversized->SetPhiBins(16384);
  const auto start = std::chrono::steady_clock::now();
  TestFailures::Add(FailureExpectation::Check(
    oversized, { "4096 x 16384", "R-buffers", "MemoryLimit" }, "an oversized grid"));
  Check(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 5.0,
    "the oversized grid is refused at once");
  // An empty grid (0 is no longer clamped to 1: -1, SCENE_SETTING, takes the input's grid).
  vtkNew<vtkSphericalCoverFilter> empty;
  empty->SetInputConnection(boxPatches->GetOutputPort(0));
  empty->SetThetaBins(0);
  TestFailures::Add(FailureExpectation::Check(
    empty, { "ThetaBins and PhiBins must be >= 1", "got 0 and" }, "an empty grid"));
  vtkNew<vtkUnstructuredGrid> bare;
  bare->ShallowCopy(boxPatches->GetOutput());
  bare->GetCellData()->RemoveArray("Emission");
  vtkNew<vtkSphericalCoverFilter> noMaterials;
  noMaterials->SetInputData(bare);
  TestFailures::Add(FailureExpectation::Check(
    noMaterials, { "lacks the material cell arrays" }, "input without materials"));
  sphcover::SphericalCover none;
  Check(
    !vtkSphericalCoverArrays::Load(boxPatches->GetOutput(), none).empty(), "patches hold no cover");
  return TestFailures::ExitCode();
}
