// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Report.h
 * @brief The JSON report of README.md#command-line (solve, render --report): per named surface its
 * area and area-weighted mean irradiance and exitant radiance, the form factors between named
 * surfaces (area-weighted over the source surface), the energy balance and the counts. The figures
 * are vtkLightPropagationFilter's (its output's field data, Core's SolutionFigures); this only
 * formats them, with the timings the commands measure (wall `timings_s` and processor
 * `timings_cpu_s` per stage; render adds its stage and `image`) and, for a solution computed in
 * the run, the bytes its cover and incident radiances hold (`memory_bytes`).
 *
 * The form factors are `form_factors.pairs`, one [from, to, F] per pair of surfaces that see each
 * other (indices of `form_factors.names`), and, for a scene of at most MatrixSurfaces named
 * surfaces, also the dense `form_factors.matrix` (row a: from surface a) that reports had before
 * the pairs: its n^2 numbers would make the report of a scene of 20,000 named parts 5 GB.
 */
#ifndef SPHCOVER_REPORT_H
#define SPHCOVER_REPORT_H

#include <nlohmann/json.hpp>

class vtkFieldData;
class vtkPolyData;

namespace sphcover_cli
{
/// What the report counts besides the illumination's figures (-1: unknown, left out).
struct ReportCounts
{
  long long Surfaces = -1;
  long long Patches = -1;
  long long PairTests = -1;
  int Shots = -1;
};

struct Solution;

/// The most named surfaces whose form factors the report also gives as the dense matrix.
constexpr long long MatrixSurfaces = 256;

/// The report of the figures in `illumination`'s field data. Throws one line when it has none.
nlohmann::json Report(vtkPolyData* illumination, const ReportCounts& counts);

/// The report of a solution computed in this run, with its timings.
nlohmann::json SolutionReport(Solution& solution);

/**
 * Adds to `report`'s `pane_limit` the light left out behind more panes than are followed, from
 * the cover's field data (CoverPaneLimit: `cover_cells`, `cover_projected_solid_angle_fraction`,
 * `direct_light_rays`) and the image's (RenderPaneLimit: `render_samples`,
 * `render_sample_fraction`); either may be null or lack its array (then its figures are left
 * out).
 */
void AddPaneLimit(nlohmann::json& report, vtkFieldData* cover, vtkFieldData* image);
}

#endif
