// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkLightPropagationSteps.h
 * @brief The steps of vtkLightPropagationFilter's RequestData, for the filters that run them in
 * another order: vtkPLightPropagationFilter (Parallel/) runs the same steps on several
 * processes, with its collectives between them. Not wrapped; not part of the filter's
 * interface.
 *
 * Contract: the steps that return a string return "" or the problem, for the caller to report
 * (and, on several processes, to agree on first); those that return a bool report their own
 * warning on the filter and return false when the user stopped them. The steps that take a
 * sphcover::RankShare (math/RankShare.h) share their items among the processes it names; the
 * default RankShare is this process alone.
 */
#ifndef vtkLightPropagationSteps_h
#define vtkLightPropagationSteps_h

#include "SphericalCoverFiltersModule.h" // for export macro

#include "cover/SphericalCover.h"
#include "math/RankShare.h"
#include "propagation/LightPropagation.h"
#include "propagation/SolutionFigures.h"
#include "scene/Material.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

class vtkDataObject;
class vtkFieldData;
class vtkLightPropagationFilter;
class vtkPolyData;
class vtkTable;

namespace vtkLightPropagationSteps
{
/// What the outputs are written from: per point and per region the propagation's results
/// (on several processes gathered from the ranks), the energy and the history.
struct PropagationResults
{
  std::vector<glm::dvec3> Irradiance;
  std::vector<glm::dvec3> Radiosity;
  std::vector<glm::dvec3> Brightness;
  /// CoverLampIrradiance (empty without the direct light's nodes).
  std::vector<glm::dvec3> Lamp;
  std::vector<glm::dvec3> Incident;
  sphcover::EnergyBalance Energy;
};

/// This rank's part of the results: per own patch (RankShare::MyItems) its irradiance,
/// radiosity, brightness and lamp irradiance, its row's length and the incident radiance of its
/// row's regions, and the energy. Collective under MPI (the lamps' irradiance and the energy
/// join inside).
struct OwnResults
{
  std::vector<glm::dvec3> PerPatch;
  std::vector<uint64_t> RowLengths;
  std::vector<glm::dvec3> Incident;
  sphcover::EnergyBalance Energy;
  std::size_t Count = 0;
  bool Lamps = false;
};

/// The cover's part of the figures (the form factors between the named surfaces of
/// `surfaces`, ReadSurfaces'), into `figures`; "" or the problem.
SPHERICALCOVERFILTERS_EXPORT std::string CoverFiguresOf(const sphcover::SphericalCover& cover,
  const sphcover::PointIllumination& surfaces,
  sphcover::CoverFigures& figures);

/// Computes the figures of the solution `points` holds (with `cover`, its cover's part, and
/// `surfaces`, its points' named surfaces as ReadSurfaces read them) and adds them to its field
/// data; "" or the problem.
SPHERICALCOVERFILTERS_EXPORT std::string StoreFigures(const sphcover::CoverFigures& cover,
  sphcover::PointIllumination illumination,
  vtkPolyData* points);

/// "" when the propagation of `rows` and the figures of `surfaces` named surfaces (0: none
/// counted) fit in `memoryLimit` MiB, else the problem.
SPHERICALCOVERFILTERS_EXPORT std::string MemoryProblem(const sphcover::SphericalCover& rows,
  const std::vector<sphcover::Material>& materials,
  int surfaces,
  double memoryLimit);

/// The cover (`withCover`: else only the points' own arrays), materials and (`named`, when the
/// points name them) surfaces of the cover points `input`, checked before the propagation: ""
/// or the problem. The figures are per named surface: a point that names none is refused
/// before the propagation, not after it.
SPHERICALCOVERFILTERS_EXPORT std::string ReadPropagationInput(vtkPolyData* input,
  bool withCover,
  bool share,
  double memoryLimit,
  sphcover::SphericalCover& cover,
  std::vector<sphcover::Material>& materials,
  bool& named,
  sphcover::PointIllumination& surfaces);

/// The exchange balance of `rows` (ExchangeBalance.h; the first 5% of the progress): its
/// factors, by entry. Under MPI (`share`) the ranks balance together, each its own rows, and a
/// rank that stops stops them all. False when stopped, with a warning on the rank whose user
/// stopped it.
SPHERICALCOVERFILTERS_EXPORT bool BalanceFactors(vtkLightPropagationFilter* self,
  const sphcover::SphericalCover& rows,
  const sphcover::RankShare& share,
  std::vector<double>& factors);

/// The rank and the rank count whose share of a cover's rows `input` holds (the field array
/// CoverRowShare of vtkSphericalCoverFilter with GatherRows off); {-1, 0} when it holds no
/// share, {-2, 0} when the array is malformed (no rank's).
SPHERICALCOVERFILTERS_EXPORT std::pair<int, int> RowShareOf(vtkDataObject* input);

/// "rank r of K's share" or "no share" of a RowShareOf.
SPHERICALCOVERFILTERS_EXPORT std::string ShareName(const std::pair<int, int>& share);

/// Warns once when the scene has panes (a material's transmittance) but the cover does not see
/// through them (`seesPanes`: the whole cover's HasPanes): a cover saved before panes were seen
/// through (SphericalCover.h, "Panes").
SPHERICALCOVERFILTERS_EXPORT void WarnOfOpaquePanes(vtkLightPropagationFilter* self,
  bool seesPanes,
  const std::vector<sphcover::Material>& materials);

/// The progressive shooting of paper §5.1 (5% to 95% of the progress), with the exchange
/// balance's `factors` when there are some (none: the cover's exchange as built); false, with a
/// warning, when aborted. `shareAmongRanks`, when given, shares the propagation among ranks
/// (vtkPLightPropagationFilter: sphcover::SharePropagation) once its frames and factors are set.
SPHERICALCOVERFILTERS_EXPORT bool Propagate(vtkLightPropagationFilter* self,
  vtkPolyData* input,
  const std::vector<double>& factors,
  sphcover::LightPropagation& propagation,
  const std::function<void(sphcover::LightPropagation&)>& shareAmongRanks);

/// Square metres per squared scene unit, from the input's SceneUnitMetres (1 without it: a scene
/// in metres, or a dataset from elsewhere): the propagation's powers are radiance times
/// solid angle times area in the scene's unit, so this factor makes them watts. False, with
/// the problem, when the array is there but not one finite length > 0.
SPHERICALCOVERFILTERS_EXPORT bool SquareMetresPerUnit(vtkFieldData* fd,
  double& factor,
  std::string& problem);

/// With the nodes of vtkSphericalCoverFilter's DirectIrradiance on the points, which patches are
/// the lamps (the bright emitters among the points, as the cover filter chose them) and whether
/// the nodes hold the first bounce: the part of the points' Irradiance that the nodes hold, as
/// the cover carries it (CoverLampIrradiance). False without the nodes.
SPHERICALCOVERFILTERS_EXPORT bool LampPatchesOf(vtkPolyData* points,
  const sphcover::SphericalCover& cover,
  const std::vector<sphcover::Material>& materials,
  std::vector<bool>& lampPatch,
  bool& firstBounce);

SPHERICALCOVERFILTERS_EXPORT OwnResults OwnResultsOf(const sphcover::LightPropagation& propagation,
  const sphcover::SphericalCover& rows,
  const std::vector<bool>& lampPatch,
  bool firstBounce);

SPHERICALCOVERFILTERS_EXPORT void SplitPerPatch(const std::vector<glm::dvec3>& perPatch,
  std::size_t count,
  bool lamps,
  PropagationResults& results);

/// Output 0's own arrays: per point Irradiance, Radiosity and Brightness (and
/// CoverLampIrradiance with the direct light's nodes); in field data the regions'
/// IncidentRadiance, the EnergyBalance (in watts: the powers times `watts`, the square metres
/// of a squared scene unit) and the PropagationStatistics.
SPHERICALCOVERFILTERS_EXPORT void WriteIllumination(const PropagationResults& results,
  int shots,
  double watts,
  vtkPolyData* output);

/// Output 0's own arrays (WriteIllumination) and, with `figures` (the cover's part), the
/// solution's figures (StoreFigures); false, with the error reported and `output` emptied, when
/// the figures cannot be summed up.
SPHERICALCOVERFILTERS_EXPORT bool WriteSolution(vtkLightPropagationFilter* self,
  const PropagationResults& results,
  int shots,
  double watts,
  const sphcover::CoverFigures* figures,
  sphcover::PointIllumination surfaces,
  vtkPolyData* output);

/// Output 1: one row per shot (shooter, relative change, unshot energy in watts: the propagation's
/// times `watts`, seconds).
SPHERICALCOVERFILTERS_EXPORT void WriteShotHistory(const std::vector<sphcover::ShotRecord>& shots,
  double watts,
  vtkTable* history);
}

#endif
