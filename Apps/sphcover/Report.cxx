// SPDX-License-Identifier: BSD-3-Clause
#include "Report.h"

#include "Pipeline.h"

#include "vtkSphericalCoverArrayNames.h"

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace sphcover_cli
{
namespace names = vtkSphericalCoverArrayNames;

nlohmann::json Report(vtkPolyData* illumination, const ReportCounts& counts)
{
  vtkFieldData* fd = illumination->GetFieldData();
  auto* surfaceNames = vtkStringArray::SafeDownCast(fd->GetAbstractArray(names::SurfaceNames));
  vtkDataArray* area = fd->GetArray(names::SurfaceArea);
  vtkDataArray* irradiance = fd->GetArray(names::SurfaceMeanIrradiance);
  vtkDataArray* radiance = fd->GetArray(names::SurfaceMeanExitantRadiance);
  vtkDataArray* pairs = fd->GetArray(names::SurfaceFormFactorPairs);
  vtkDataArray* factors = fd->GetArray(names::SurfaceFormFactorValues);
  vtkDataArray* balance = fd->GetArray(names::EnergyBalance);
  vtkDataArray* statistics = fd->GetArray(names::SolutionStatistics);
  const vtkIdType groups = surfaceNames ? surfaceNames->GetNumberOfValues() : 0;
  auto holds = [](vtkDataArray* array, int components, vtkIdType tuples)
  {
    return array && array->GetNumberOfComponents() == components &&
      array->GetNumberOfTuples() == tuples;
  };
  if (!surfaceNames || !holds(area, 1, groups) || !holds(irradiance, 3, groups) ||
    !holds(radiance, 3, groups) || !pairs || !holds(pairs, 2, pairs->GetNumberOfTuples()) ||
    !holds(factors, 1, pairs->GetNumberOfTuples()) || !holds(balance, 3, 2) ||
    !holds(statistics, 3, 1))
  {
    throw std::runtime_error("the illumination lacks the solution's figures (SurfaceArea, "
                             "SurfaceFormFactorPairs, SolutionStatistics: "
                             "vtkLightPropagationFilter)");
  }
  auto triple = [](vtkDataArray* array, vtkIdType tuple)
  {
    return nlohmann::json::array({ array->GetComponent(tuple, 0),
      array->GetComponent(tuple, 1),
      array->GetComponent(tuple, 2) });
  };

  nlohmann::json report;
  report["surfaces"] = nlohmann::json::array();
  report["form_factors"]["names"] = nlohmann::json::array();
  for (vtkIdType a = 0; a < groups; ++a)
  {
    report["surfaces"].push_back({ { "name", surfaceNames->GetValue(a) },
      { "area", area->GetComponent(a, 0) },
      { "mean_irradiance", triple(irradiance, a) },
      { "mean_exitant_radiance", triple(radiance, a) } });
    report["form_factors"]["names"].push_back(surfaceNames->GetValue(a));
  }
  // The pairs as the field data lists them, by row; the dense matrix from them for a scene of
  // few surfaces (the pairs not listed are 0, as the matrix's were).
  nlohmann::json& listed = report["form_factors"]["pairs"] = nlohmann::json::array();
  const bool dense = groups <= MatrixSurfaces;
  std::vector<double> matrix(dense ? static_cast<std::size_t>(groups * groups) : 0, 0.0);
  for (vtkIdType k = 0; k < pairs->GetNumberOfTuples(); ++k)
  {
    const double from = pairs->GetComponent(k, 0);
    const double to = pairs->GetComponent(k, 1);
    if (!(from >= 0.0 && from < groups && to >= 0.0 && to < groups))
    {
      throw std::runtime_error("the illumination's SurfaceFormFactorPairs names surface " +
        std::to_string(from < 0.0 || from >= groups ? from : to) + ", not one of the " +
        std::to_string(groups) + " SurfaceNames");
    }
    const vtkIdType a = static_cast<vtkIdType>(from);
    const vtkIdType b = static_cast<vtkIdType>(to);
    const double value = factors->GetComponent(k, 0);
    listed.push_back({ a, b, value });
    if (dense)
    {
      matrix[static_cast<std::size_t>(a * groups + b)] = value;
    }
  }
  if (dense)
  {
    report["form_factors"]["matrix"] = nlohmann::json::array();
    for (vtkIdType a = 0; a < groups; ++a)
    {
      report["form_factors"]["matrix"].push_back(
        std::vector<double>(matrix.begin() + static_cast<std::ptrdiff_t>(a * groups),
          matrix.begin() + static_cast<std::ptrdiff_t>((a + 1) * groups)));
    }
  }
  // The scene's length unit: areas are in its square, powers already in watts
  // (vtkLightPropagationFilter converts them with SceneUnitMetres).
  auto* unitName = vtkStringArray::SafeDownCast(fd->GetAbstractArray(names::SceneUnit));
  vtkDataArray* unitMetres = fd->GetArray(names::SceneUnitMetres);
  report["unit"] = { { "name",
                       unitName && unitName->GetNumberOfValues() == 1 ? unitName->GetValue(0)
                                                                      : std::string("m") },
    { "metres",
      unitMetres && unitMetres->GetNumberOfTuples() == 1 ? unitMetres->GetComponent(0, 0) : 1.0 } };
  report["energy"] = { { "emitted_w", triple(balance, 0) },
    { "absorbed_w", triple(balance, 1) },
    { "relative_imbalance", statistics->GetComponent(0, 2) } };
  report["counts"] = { { "characteristic_points",
                         static_cast<long long>(statistics->GetComponent(0, 0)) },
    { "strips", static_cast<unsigned long long>(statistics->GetComponent(0, 1)) } };
  if (counts.Surfaces >= 0)
  {
    report["counts"]["surfaces"] = counts.Surfaces;
  }
  if (counts.Patches >= 0)
  {
    report["counts"]["patches"] = counts.Patches;
  }
  if (counts.PairTests >= 0)
  {
    report["counts"]["pair_tests"] = counts.PairTests;
  }
  if (counts.Shots >= 0)
  {
    report["counts"]["shots"] = counts.Shots;
  }
  return report;
}

void AddPaneLimit(nlohmann::json& report, vtkFieldData* cover, vtkFieldData* image)
{
  vtkDataArray* drops = cover ? cover->GetArray(names::CoverPaneLimit) : nullptr;
  if (drops && drops->GetNumberOfComponents() == 3 && drops->GetNumberOfTuples() == 1)
  {
    report["pane_limit"]["cover_cells"] = static_cast<long long>(drops->GetComponent(0, 0));
    report["pane_limit"]["cover_projected_solid_angle_fraction"] = drops->GetComponent(0, 1);
    report["pane_limit"]["direct_light_rays"] = static_cast<long long>(drops->GetComponent(0, 2));
  }
  vtkDataArray* samples = image ? image->GetArray(names::RenderPaneLimit) : nullptr;
  if (samples && samples->GetNumberOfComponents() == 2 && samples->GetNumberOfTuples() == 1)
  {
    report["pane_limit"]["render_samples"] = static_cast<long long>(samples->GetComponent(0, 0));
    report["pane_limit"]["render_sample_fraction"] = samples->GetComponent(0, 1);
  }
}

nlohmann::json SolutionReport(Solution& solution)
{
  ReportCounts counts;
  counts.Surfaces = solution.Reader->GetOutput()->GetNumberOfCells();
  counts.Patches = solution.Subdivision->GetOutput()->GetNumberOfCells();
  counts.PairTests = static_cast<long long>(solution.Subdivision->GetPairTests());
  counts.Shots = solution.Propagation->GetShots();
  nlohmann::json report = Report(solution.Propagation->GetOutput(), counts);
  report["timings_s"] = solution.Timings();
  report["timings_cpu_s"] = solution.CpuTimings();
  // The cover stage's parts on this rank (vtkSphericalCoverFilter::GetStageSeconds).
  const double* stages = solution.Cover->GetStageSeconds();
  report["cover_stages_s"] = {
    { "refinement", stages[0] }, { "rows", stages[1] }, { "direct_light", stages[2] }
  };
  // The ranks the cover was built on (vtkSphericalCoverFilter's CoverRankFigures, present when
  // there were several): per rank its receivers, wall seconds and the bytes of its rows.
  vtkDataArray* ranks =
    solution.Cover->GetOutput()->GetFieldData()->GetArray(names::CoverRankFigures);
  report["ranks"] = ranks && ranks->GetNumberOfComponents() == 3 ? ranks->GetNumberOfTuples() : 1;
  AddPaneLimit(report, solution.Cover->GetOutput()->GetFieldData(), nullptr);
  if (ranks && ranks->GetNumberOfComponents() == 3)
  {
    report["cover_ranks"] = nlohmann::json::array();
    for (vtkIdType r = 0; r < ranks->GetNumberOfTuples(); ++r)
    {
      report["cover_ranks"].push_back(
        { { "receivers", static_cast<long long>(ranks->GetComponent(r, 0)) },
          { "seconds", ranks->GetComponent(r, 1) },
          { "bytes", static_cast<long long>(ranks->GetComponent(r, 2)) } });
    }
  }
  // The ranks the propagation ran on (vtkLightPropagationFilter::GetRankFigures): per rank its
  // receivers, the entries of its rows, the bytes of its propagation state and its seconds.
  const std::vector<double>& shooting = solution.Propagation->GetRankFigures();
  if (shooting.size() >= 4)
  {
    report["propagation_ranks"] = nlohmann::json::array();
    for (std::size_t r = 0; r + 4 <= shooting.size(); r += 4)
    {
      report["propagation_ranks"].push_back({ { "receivers", static_cast<long long>(shooting[r]) },
        { "entries", static_cast<long long>(shooting[r + 1]) },
        { "state_bytes", static_cast<long long>(shooting[r + 2]) },
        { "seconds", shooting[r + 3] } });
    }
  }
  // The processes' peak resident memory up to the equilibrium, per rank (the rendering after it
  // is rank 0's alone): what each machine of a cluster must hold.
  report["peak_resident_bytes"] = nlohmann::json::array();
  for (double bytes : solution.PeakResidentBytes)
  {
    report["peak_resident_bytes"].push_back(static_cast<long long>(bytes));
  }
  // What the solution holds: the cover (its strips, entries and rows, paper §3.3, stored as
  // field arrays) and the propagation's state of one incident radiance per region h_ij (§5.1),
  // over the ranks when there are several. The stages' working memory (R-buffers, weight
  // tables) comes and goes.
  report["memory_bytes"] = { { "cover", static_cast<unsigned long long>(solution.CoverBytes) },
    { "incident_radiance", static_cast<unsigned long long>(solution.IncidentRadianceBytes) } };
  return report;
}
}
