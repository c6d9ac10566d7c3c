// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Pipeline.h
 * @brief The VTK pipeline the commands run: the reader, then the subdivision, the spherical
 * cover and the light propagation (paper §4, §3.3, §5.1), each stage with a progress bar and its
 * times (wall seconds from its first to its last progress report, and the process's processor
 * seconds over its update, all threads); a failing stage throws its first error as one line.
 */
#ifndef SPHCOVER_PIPELINE_H
#define SPHCOVER_PIPELINE_H

#include "ErrorCollector.h"

#include "vtkIntervalSubdivisionFilter.h"
#include "vtkPLightPropagationFilter.h"
#include "vtkPSphericalCoverFilter.h"
#include "vtkPatchSceneReader.h"

#include "scene/Scene.h"

#include <nlohmann/json.hpp>
#include <vtkNew.h>

#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;

namespace sphcover_cli
{
struct Options;

/// Updates an algorithm (`piece` > 0: piece `piece` of `pieces`, vtkScenePieces.h); on failure
/// throws its first error as one line.
void Run(vtkAlgorithm* algorithm, ErrorCollector& errors, int piece = 0, int pieces = 1);

/// Processor seconds the whole process has used so far, all its threads (std::clock): the
/// difference over a stage is what the stage cost in processor time, whatever the number of
/// threads and however loaded the machine (the report's `timings_cpu_s`).
double ProcessorSeconds();

/// The scene's settings block as the reader passed it on, with the --set overrides applied.
sphcover::SceneSettings SettingsOf(vtkDataObject* surfaces, const std::vector<std::string>& sets);

/// The scene file through the reader, and (Solve) the stages up to the equilibrium.
struct Solution
{
  vtkNew<vtkPatchSceneReader> Reader;
  vtkNew<vtkIntervalSubdivisionFilter> Subdivision;
  vtkNew<vtkPSphericalCoverFilter> Cover;
  vtkNew<vtkPLightPropagationFilter> Propagation;
  ErrorCollector Errors;
  double ReadSeconds = 0.0;
  double SubdivideSeconds = 0.0;
  double CoverSeconds = 0.0;
  double PropagateSeconds = 0.0;
  /// Processor seconds of each stage (ProcessorSeconds over its update).
  double ReadCpuSeconds = 0.0;
  double SubdivideCpuSeconds = 0.0;
  double CoverCpuSeconds = 0.0;
  double PropagateCpuSeconds = 0.0;
  /// After Solve: each rank's peak resident bytes (getrusage), in rank order (one alone).
  std::vector<double> PeakResidentBytes;
  /// After Solve: the bytes of the solution's cover arrays and of its regions' IncidentRadiance,
  /// over all ranks (the whole solution's, gathered on rank 0 or kept in pieces).
  double CoverBytes = 0.0;
  double IncidentRadianceBytes = 0.0;

  /// Reads the scene (its surfaces, cameras, settings and fingerprint in field data).
  void Read(const Options& options, bool progress = true);

  /// After Read: the interval subdivision with the scene's settings (the filter reads them from
  /// the reader's output), the --set overrides and the options' budgets.
  void Subdivide(const Options& options);

  /// After Read: checks the cover grid against --memory-limit, then subdivides, covers and
  /// propagates with the scene's settings and the options. Under mpiexec the ranks cover and
  /// propagate together, rank 0 holding the whole scene and the others empty pieces (as under
  /// pvbatch): rank 0 alone ends with the cover and the solution, or (`gather` false) every
  /// rank with its piece of the solution (vtkLightPropagationFilter's GatherSolution off), so
  /// that no rank ever holds the whole cover. Collective.
  void Solve(const Options& options, bool gather = true);

  /// The stages' seconds, as the report's `timings_s`.
  nlohmann::json Timings() const;

  /// The stages' processor seconds, as the report's `timings_cpu_s` (same keys as Timings).
  nlohmann::json CpuTimings() const;
};
}

#endif
