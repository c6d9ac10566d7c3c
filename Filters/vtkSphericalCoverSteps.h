// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkSphericalCoverSteps.h
 * @brief The steps of vtkSphericalCoverFilter's RequestData, for the filters that run them in
 * another order: vtkPSphericalCoverFilter (Parallel/) runs the same steps on several processes,
 * with its collectives between them. Not wrapped; not part of the filter's interface.
 *
 * Contract: each step takes the filter whose properties it reads (and whose progress it
 * reports), reports its own error or warning on that filter and returns false when it failed
 * or was aborted. The steps that take a sphcover::RankShare (math/RankShare.h) share their
 * items among the processes it names; the default RankShare is this process alone.
 */
#ifndef vtkSphericalCoverSteps_h
#define vtkSphericalCoverSteps_h

#include "SphericalCoverFiltersModule.h" // for export macro

#include "cover/DirectIrradiance.h"
#include "cover/SphericalCover.h"
#include "math/RankShare.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <vtkType.h>

#include <chrono>
#include <cstddef>
#include <memory>
#include <vector>

class vtkDataSet;
class vtkPolyData;
class vtkSphericalCoverFilter;
class vtkTable;

namespace sphcover
{
class RayCaster;
}

namespace vtkSphericalCoverSteps
{
/// What the cover may use: the threads that build R-buffers at once and the MemoryLimit in
/// bytes.
struct MemoryBudget
{
  std::size_t Threads;
  std::size_t LimitBytes;
};

/// The patches a cover is built of, its options and budget, after the refinement.
struct CoverInput
{
  sphcover::Scene Scene;
  std::vector<sphcover::Patch> Patches;
  /// The input cell each patch was cut from (the identity without refinement).
  std::vector<vtkIdType> CellOfPatch;
  sphcover::SphericalCoverOptions Options;
  MemoryBudget Budget{ 1, 0 };
  std::vector<glm::dvec3> Emission;
  /// Where the cover's own progress starts (after the refinement's).
  double CoverStart = 0.0;
  /// The one ray caster of the refined patches, shared by the ray fill (its memory estimate
  /// and its rows) and the lamps' direct light; null when neither casts rays.
  std::shared_ptr<const sphcover::RayCaster> Rays;
};

/// Per characteristic point the projected solid angle its hemisphere covers and the sources
/// it sees (output 0's CoveredProjectedSolidAngle and VisibleSources).
struct PointCoverage
{
  std::vector<double> Covered;
  std::vector<int> Visible;
};

SPHERICALCOVERFILTERS_EXPORT double SecondsSince(std::chrono::steady_clock::time_point start);

/// The input's patches, the options from the properties and the refinement (paper §4.3 Steps
/// 3 and 5), refused before any R-buffer exists when the grid's working memory cannot fit.
SPHERICALCOVERFILTERS_EXPORT bool PrepareCover(vtkSphericalCoverFilter* self,
  vtkDataSet* input,
  CoverInput& prepared);

/// The refinement of the prepared patches (paper §4.3 Steps 3 and 5) and what depends on the
/// refined patches: their emission, the measured lamps and the ray caster.
SPHERICALCOVERFILTERS_EXPORT bool RefineCover(vtkSphericalCoverFilter* self,
  const sphcover::RankShare& share,
  CoverInput& prepared);

/// Whether the cover's memory fits the budget. Without patches this is the working memory of
/// the grid on every thread (the refinement builds R-buffers too), from the options alone;
/// with them, an estimate of the cover from a few rows actually built.
SPHERICALCOVERFILTERS_EXPORT bool MemoryFits(vtkSphericalCoverFilter* self,
  const std::vector<sphcover::Patch>& patches,
  const sphcover::SphericalCoverOptions& options,
  const MemoryBudget& budget,
  const std::shared_ptr<const sphcover::RayCaster>& rays);

/// The lamps' direct light on the patches' nodes when DirectIrradianceNodes asks for it.
SPHERICALCOVERFILTERS_EXPORT bool ComputeDirectIrradianceOf(vtkSphericalCoverFilter* self,
  const sphcover::RankShare& share,
  const CoverInput& prepared,
  sphcover::DirectIrradianceNodes& direct);

/// The coverage of every point of a whole cover.
SPHERICALCOVERFILTERS_EXPORT PointCoverage CoverageOf(const sphcover::SphericalCover& cover);

/// Both outputs of a built cover (or of a share of its rows): the characteristic points with
/// `coverage` and the direct light's nodes, and the strips (GenerateStripTable).
SPHERICALCOVERFILTERS_EXPORT void WriteOutputs(vtkSphericalCoverFilter* self,
  vtkDataSet* input,
  const CoverInput& prepared,
  const sphcover::SphericalCover& cover,
  const PointCoverage& coverage,
  const sphcover::DirectIrradianceNodes& direct,
  vtkPolyData* pointsOut,
  vtkTable* stripsOut);
}

#endif
