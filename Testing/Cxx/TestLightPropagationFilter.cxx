// SPDX-License-Identifier: BSD-3-Clause
// vtkLightPropagationFilter (Documentation/Pipeline.md#light-propagation), through the whole
// pipeline of VTK filters:
// - white furnace in a closed curved enclosure (the subdivided Bezier sphere): every point's
//   exitant radiance is Le / (1 - rho) per band within 0.5%, and emitted = absorbed power;
// - the Cornell box: colour bleeds from the red and green walls onto the back wall (its red /
//   green ratio is higher near the red wall than near the green wall);
// - MaximumShots stops early with a history of that many shots;
// - the teapot room (mirror wall, phong teapot) propagates: the mirror's Radiosity is its
//   emission (0) while its Brightness carries the light it reflects, and the energy is
//   conserved up to what escapes the room (none: it is closed);
// - the white furnace with the tabulated clay BRDF (furnace_clay.scene): Brightness / pi is
//   Le / (1 - albedo) within 1%;
// - a missing BRDF table and an input without a cover give one clear error.
#include "FailureExpectation.h"
#include "TestFailures.h"
#include "vtkIntervalSubdivisionFilter.h"
#include "vtkLightPropagationFilter.h"
#include "vtkPatchSceneReader.h"
#include "vtkSphericalCoverFilter.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <cmath>
#include <iostream>
#include <string>

namespace
{
using TestFailures::Check;

/// reader -> subdivision (MaxLevel) -> cover -> propagation, all updated.
struct Pipeline
{
  vtkNew<vtkPatchSceneReader> Reader;
  vtkNew<vtkIntervalSubdivisionFilter> Subdivision;
  vtkNew<vtkSphericalCoverFilter> Cover;
  vtkNew<vtkLightPropagationFilter> Propagation;

  Pipeline(const std::string& scene, int maxLevel)
  {
    this->Reader->SetFileName((std::string(SPHCOVER_DATA_DIR "/scenes/") + scene).c_str());
    this->Subdivision->SetInputConnection(this->Reader->GetOutputPort());
    this->Subdivision->SetMaxLevel(maxLevel);
    this->Cover->SetInputConnection(this->Subdivision->GetOutputPort(0));
    this->Propagation->SetInputConnection(this->Cover->GetOutputPort(0));
  }
};
}

int TestLightPropagationFilter(int, char*[])
{
  // White furnace, curved and closed.
  {
    Pipeline furnace("furnace_sphere.scene", 1);
    furnace.Propagation->Update();
    vtkPolyData* lit = furnace.Propagation->GetOutput();
    vtkDataArray* radiance = lit->GetPointData()->GetArray("Radiosity");
    vtkDataArray* rho = lit->GetPointData()->GetArray("Diffuse");
    vtkDataArray* le = lit->GetPointData()->GetArray("Emission");
    double worst = 0.0;
    for (vtkIdType i = 0; i < lit->GetNumberOfPoints(); ++i)
    {
      for (int band = 0; band < 3; ++band)
      {
        const double expected = le->GetComponent(i, band) / (1.0 - rho->GetComponent(i, band));
        worst = std::max(worst, std::fabs(radiance->GetComponent(i, band) / expected - 1.0));
      }
    }
    vtkDataArray* balance = lit->GetFieldData()->GetArray("EnergyBalance");
    double imbalance = 0.0;
    for (int band = 0; band < 3; ++band)
    {
      imbalance = std::max(imbalance,
        std::fabs(balance->GetComponent(1, band) / balance->GetComponent(0, band) - 1.0));
    }
    std::cout << "furnace sphere: " << lit->GetNumberOfPoints() << " points, "
              << furnace.Propagation->GetShots()
              << " shots, worst |L / (Le/(1-rho)) - 1| = " << worst << ", energy imbalance "
              << imbalance << "\n";
    Check(worst < 5e-3, "furnace: exitant radiance within 0.5% of Le/(1-rho)");
    Check(imbalance < 1e-3, "furnace: emitted = absorbed within 0.1%");
    auto* history = vtkTable::SafeDownCast(furnace.Propagation->GetOutputDataObject(1));
    Check(history && history->GetNumberOfRows() == furnace.Propagation->GetShots(),
      "one history row per shot");
    Check(lit->GetFieldData()->GetArray("IncidentRadiance") != nullptr,
      "the incident radiance of every region is in the output");

    furnace.Propagation->SetMaximumShots(5);
    furnace.Propagation->Update();
    Check(furnace.Propagation->GetShots() == 5 &&
        vtkTable::SafeDownCast(furnace.Propagation->GetOutputDataObject(1))->GetNumberOfRows() == 5,
      "MaximumShots stops after that many shots");
  }

  // Colour bleeding in the Cornell box: on the back wall, red / green is higher near the red
  // wall (x ~ 550) than near the green wall (x ~ 0).
  {
    Pipeline box("cornell_box.scene", 2);
    box.Propagation->Update();
    vtkPolyData* lit = box.Propagation->GetOutput();
    vtkDataArray* radiance = lit->GetPointData()->GetArray("Radiosity");
    vtkDataArray* nameId = lit->GetPointData()->GetArray("SurfaceNameId");
    auto* names =
      vtkStringArray::SafeDownCast(lit->GetFieldData()->GetAbstractArray("SurfaceNames"));
    double nearRed[2] = { 0, 0 };
    double nearGreen[2] = { 0, 0 };
    for (vtkIdType i = 0; i < lit->GetNumberOfPoints(); ++i)
    {
      if (names->GetValue(static_cast<vtkIdType>(nameId->GetComponent(i, 0))) != "back_wall")
      {
        continue;
      }
      double p[3];
      lit->GetPoint(i, p);
      double* side = p[0] > 450 ? nearRed : (p[0] < 100 ? nearGreen : nullptr);
      if (side)
      {
        side[0] += radiance->GetComponent(i, 0);
        side[1] += radiance->GetComponent(i, 1);
      }
    }
    const double redRatio = nearRed[0] / nearRed[1];
    const double greenRatio = nearGreen[0] / nearGreen[1];
    std::cout << "Cornell back wall red/green: near the red wall " << redRatio
              << ", near the green wall " << greenRatio << "\n";
    // The white paint alone gives 0.886/0.699 = 1.27 for white light; the bleeding must move
    // each side clearly (10%) away from the other.
    Check(redRatio > 1.1 * greenRatio, "red bleeds onto the back wall near the red wall");
  }

  // Non-diffuse materials through the filter: the teapot room's mirror wall and phong teapot.
  {
    Pipeline room("teapot_room.scene", 0);
    room.Propagation->SetConvergenceTolerance(1e-4);
    room.Propagation->Update();
    vtkPolyData* lit = room.Propagation->GetOutput();
    vtkDataArray* type = lit->GetPointData()->GetArray("MaterialType");
    vtkDataArray* radiosity = lit->GetPointData()->GetArray("Radiosity");
    vtkDataArray* brightness = lit->GetPointData()->GetArray("Brightness");
    Check(
      lit->GetNumberOfPoints() > 0 && room.Propagation->GetShots() > 0, "teapot room: propagated");
    int mirrors = 0;
    for (vtkIdType i = 0; i < lit->GetNumberOfPoints(); ++i)
    {
      if (static_cast<int>(type->GetComponent(i, 0)) == 1)
      {
        ++mirrors;
        Check(radiosity->GetComponent(i, 0) == 0.0, "a mirror has no Lambertian radiance");
        Check(brightness->GetComponent(i, 0) > 0.0, "a mirror reflects light");
      }
    }
    Check(mirrors > 0, "teapot room has mirror points");
  }
  {
    Pipeline furnace("furnace_clay.scene", 1);
    furnace.Propagation->SetConvergenceTolerance(1e-6);
    furnace.Propagation->Update();
    vtkPolyData* lit = furnace.Propagation->GetOutput();
    vtkDataArray* brightness = lit->GetPointData()->GetArray("Brightness");
    const double albedo[3] = { 0.75, 0.55, 0.35 };
    double worst = 0.0;
    for (vtkIdType i = 0; i < lit->GetNumberOfPoints(); ++i)
    {
      for (int band = 0; band < 3; ++band)
      {
        worst = std::max(
          worst, std::fabs(brightness->GetComponent(i, band) / M_PI * (1.0 - albedo[band]) - 1.0));
      }
    }
    std::cout << "clay furnace: " << lit->GetNumberOfPoints() << " points, "
              << furnace.Propagation->GetShots()
              << " shots, worst |B / pi / (Le/(1-a)) - 1| = " << worst << "\n";
    Check(lit->GetNumberOfPoints() > 0 && worst < 0.01,
      "tabulated furnace: Brightness / pi within 1% of Le / (1 - albedo)");
  }

  // Errors.
  {
    Pipeline missing("furnace_clay.scene", 0);
    missing.Cover->Update();
    vtkNew<vtkPolyData> points;
    points->DeepCopy(missing.Cover->GetOutput());
    auto* files =
      vtkStringArray::SafeDownCast(points->GetFieldData()->GetAbstractArray("MaterialFiles"));
    for (vtkIdType k = 0; files && k < files->GetNumberOfValues(); ++k)
    {
      files->SetValue(k, "/nonexistent/clay.brdf.csv");
    }
    vtkNew<vtkLightPropagationFilter> noTable;
    noTable->SetInputData(points);
    TestFailures::Add(FailureExpectation::Check(
      noTable, { "/nonexistent/clay.brdf.csv", "cannot open file" }, "a missing BRDF table"));
    vtkNew<vtkPolyData> empty;
    vtkNew<vtkLightPropagationFilter> noCover;
    noCover->SetInputData(empty);
    TestFailures::Add(
      FailureExpectation::Check(noCover, { "no spherical cover" }, "input without a cover"));
  }
  return TestFailures::ExitCode();
}
