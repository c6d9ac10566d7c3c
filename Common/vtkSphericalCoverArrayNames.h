// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkSphericalCoverArrayNames.h
 * @brief The names of the arrays every stage reads and writes (Documentation/Pipeline.md): one
 * place for all.
 *
 * ParaView users colour by these names and scripts read them, so they are a contract.
 */
#ifndef vtkSphericalCoverArrayNames_h
#define vtkSphericalCoverArrayNames_h

namespace vtkSphericalCoverArrayNames
{
// Reader output, cell data (Documentation/Pipeline.md#reader).
constexpr const char* SurfaceId = "SurfaceId";
constexpr const char* SurfaceNameId = "SurfaceNameId";
constexpr const char* MaterialId = "MaterialId";
constexpr const char* MaterialType = "MaterialType";
constexpr const char* Emission = "Emission";
constexpr const char* Diffuse = "Diffuse";
constexpr const char* Specular = "Specular";
constexpr const char* PhongExponent = "PhongExponent";
constexpr const char* TwoSided = "TwoSided";
/// Reader output, point data, 2 components: the texture coordinates (u, v) of each control point
/// in its surface's parameter square, the active TCoords: a Bezier cell interpolates them to the
/// exact (u, v) (the Bernstein basis reproduces linear functions), so a texture shown on the
/// reader's output in ParaView lies where the solution's does (Data/scenes/FORMAT.md, "texture").
constexpr const char* TextureCoordinates = "TextureCoordinates";
/// 3 components: the material's transmittance (a thin pane, Data/scenes/FORMAT.md; 0: opaque).
constexpr const char* Transmittance = "Transmittance";
constexpr const char* HigherOrderDegrees = "HigherOrderDegrees";

// Reader output, field data.
constexpr const char* SurfaceNames = "SurfaceNames";
constexpr const char* MaterialNames = "MaterialNames";
constexpr const char* MaterialTypeNames = "MaterialTypeNames";
constexpr const char* MaterialFiles = "MaterialFiles";
/// Per material: the absolute path of its texture PNG ("" for none) and its encoding ("srgb",
/// "linear"), indexed by MaterialId (Data/scenes/FORMAT.md, "texture").
constexpr const char* MaterialTextures = "MaterialTextures";
constexpr const char* MaterialTextureEncodings = "MaterialTextureEncodings";
constexpr const char* CameraNames = "CameraNames";
/// 12 components: position (3), focal point (3), view up (3), view angle, width, height.
constexpr const char* CameraParameters = "CameraParameters";
/// 4 named components: theta_bins, phi_bins, max_level, tolerance.
constexpr const char* SceneSettings = "SceneSettings";
constexpr const char* SourceFile = "SourceFile";
/// The scene's length unit (its file's "unit", Data/scenes/FORMAT.md): one string, the unit's
/// name ("mm", "m", ...), and SceneUnitMetres, one double, its length in metres. Lengths and
/// areas are in this unit; the powers the stages report (EnergyBalance, UnshotEnergy) are
/// converted to watts with it.
constexpr const char* SceneUnit = "SceneUnit";
constexpr const char* SceneUnitMetres = "SceneUnitMetres";
/// One string: the scene's fingerprint (sphcover::Fingerprint), carried to every stage's output
/// so that a saved solution can tell the scene it was solved from.
constexpr const char* SceneFingerprint = "SceneFingerprint";

// Interval subdivision (Documentation/Pipeline.md#interval-subdivision): patches (cell data) and
// characteristic points (point data).
constexpr const char* PatchId = "PatchId";
/// Cover points: the cell of the cover's input (the subdivision's Patches) a point's patch was
/// cut from by the cover's refinement (PatchId numbers the refined patches).
constexpr const char* InputPatchId = "InputPatchId";
constexpr const char* Level = "Level";
/// 4 components: u0, u1, v0, v1 of the patch in its surface's parameters.
constexpr const char* UVRange = "UVRange";
constexpr const char* Area = "Area";
constexpr const char* SplitReason = "SplitReason";
constexpr const char* SplitReasonNames = "SplitReasonNames";
constexpr const char* Normals = "Normals";
constexpr const char* UV = "UV";
/// Field data, named components: pair tests, sweeps.
constexpr const char* SubdivisionStatistics = "SubdivisionStatistics";
/// Field data, 7 named components: the settings the subdivision used (max_level, theta_bins,
/// phi_bins and the tolerances of the four criteria), its properties or the scene's.
constexpr const char* SubdivisionSettings = "SubdivisionSettings";

// Spherical cover (Documentation/Pipeline.md#spherical-cover): points' point data, the cover in
// field data, the strip table.
constexpr const char* Tangents = "Tangents";
constexpr const char* CoveredProjectedSolidAngle = "CoveredProjectedSolidAngle";
constexpr const char* VisibleSources = "VisibleSources";
constexpr const char* CoverGrid = "CoverGrid";
constexpr const char* CoverRowOffsets = "CoverRowOffsets";
constexpr const char* CoverEntries = "CoverEntries";
constexpr const char* CoverUnoccluded = "CoverUnoccluded";
constexpr const char* CoverStrips = "CoverStrips";
constexpr const char* CoverStripDepths = "CoverStripDepths";
constexpr const char* CoverMeasures = "CoverMeasures";
/// Panes (SphericalCover.h "Panes"), all three or none: per entry its layer (uint8) and filter
/// (3 floats, RGB, one component), per patch its transmittance (3 floats, one component).
constexpr const char* CoverLayers = "CoverLayers";
constexpr const char* CoverFilters = "CoverFilters";
constexpr const char* CoverTransmittances = "CoverTransmittances";
/// Field data of the cover's output, 1 tuple x 3 (double): the light left out behind more panes
/// than the layers keep (issue 39 item 6): the cells of the rows whose last layer is still a pane
/// (SphericalCover::PaneLimit; MaxPaneDepth 4 behind the first), their share of the hemispheres'
/// projected solid angle weighted by the panes' transmittance (of pi times the rows), and the
/// direct light's shadow and bounce rays that met more than MaxPanesPerRay (8) panes. Zeros
/// without panes.
constexpr const char* CoverPaneLimit = "CoverPaneLimit";
/// Field data of a radiance image, 1 tuple x 2 (double): the samples whose ray met more than
/// RadianceRenderer::MaxPanesPerSample (8) panes (the light behind left out) and their share of
/// the image's samples.
constexpr const char* RenderPaneLimit = "RenderPaneLimit";
/// Field data of a cover built on K > 1 ranks, K tuples x 3 (double): per rank the receivers
/// whose rows it built, the wall seconds it took and the bytes of its row block.
constexpr const char* CoverRankFigures = "CoverRankFigures";
/// Field data of one rank's share of a cover built on K > 1 ranks that keep their rows
/// (vtkSphericalCoverFilter's GatherRows off), 2 ints: the rank r and K. The cover arrays then
/// hold the rows of receivers r, r + K, ... only (RowShares::BuildRowsOf), the others
/// empty; the point data is every point's.
constexpr const char* CoverRowShare = "CoverRowShare";
/// Point data, 3 n^2 components: the lamps' direct irradiance (RGB, W m^-2) at the n x n nodes
/// of every point's patch, node (i, j) band b at component (j n + i) 3 + b (Core's
/// DirectIrradiance.h).
constexpr const char* DirectIrradiance = "DirectIrradiance";
/// Field data, 1 value: the first bounce's rays per side the nodes of DirectIrradiance were
/// gathered with (0: they hold the direct light only).
constexpr const char* DirectBounceRays = "DirectBounceRays";
constexpr const char* Receiver = "Receiver";
constexpr const char* Source = "Source";
constexpr const char* Theta = "Theta";
constexpr const char* PhiBegin = "PhiBegin";
constexpr const char* PhiEnd = "PhiEnd";
constexpr const char* R = "R";

// Hemisphere extractor (Documentation/Pipeline.md#inspection-filters): cell data of the hemisphere
// image and mesh (with Source, SurfaceId, R).
/// The cosine-weighted measure of a (theta, phi) cell, dphi (cos 2 theta0 - cos 2 theta1) / 4.
constexpr const char* ProjectedSolidAngle = "ProjectedSolidAngle";

// Propagation (Documentation/Pipeline.md#light-propagation): points' point data, field data, the
// convergence history.
constexpr const char* Irradiance = "Irradiance";
constexpr const char* Radiosity = "Radiosity";
/// Point data, 3 components, with DirectIrradiance: the part of Irradiance the nodes hold (the
/// lamps' direct light and, with DirectBounceRays > 0, its first bounce) as the cover's regions
/// carry it (LightPropagation::LampIrradiance); a renderer that adds the nodes takes it off.
constexpr const char* CoverLampIrradiance = "CoverLampIrradiance";
constexpr const char* Brightness = "Brightness";
constexpr const char* IncidentRadiance = "IncidentRadiance";
/// 2 tuples of 3 bands: emitted and absorbed power, W.
constexpr const char* EnergyBalance = "EnergyBalance";
constexpr const char* Shot = "Shot";
constexpr const char* Shooter = "Shooter";
constexpr const char* MaxChange = "MaxChange";
constexpr const char* UnshotEnergy = "UnshotEnergy";
constexpr const char* Seconds = "Seconds";
/// Field data, named component: Shots (of the propagation).
constexpr const char* PropagationStatistics = "PropagationStatistics";
/// Field data, the figures of the solution (Core's SolutionFigures), one tuple per entry of
/// SurfaceNames: area (in the scene unit's square), area-weighted mean irradiance (3) and
/// exitant radiance (3).
constexpr const char* SurfaceArea = "SurfaceArea";
constexpr const char* SurfaceMeanIrradiance = "SurfaceMeanIrradiance";
constexpr const char* SurfaceMeanExitantRadiance = "SurfaceMeanExitantRadiance";
/// Field data, the form factors between the named surfaces that see each other (Core's
/// SurfaceFormFactors), one tuple per pair, by the first surface then the second: the pair's
/// indices of SurfaceNames (int, components From and To) and F from the first to the second
/// (double). A pair not listed does not see each other (F = 0). Sparse, because the n x n
/// matrix of a scene of thousands of named parts does not fit in memory.
constexpr const char* SurfaceFormFactorPairs = "SurfaceFormFactorPairs";
constexpr const char* SurfaceFormFactorValues = "SurfaceFormFactorValues";
/// Field data, named components: CharacteristicPoints, Strips, RelativeImbalance.
constexpr const char* SolutionStatistics = "SolutionStatistics";

// Rendering (Documentation/Pipeline.md#rendering): point data of the image (with SurfaceId).
constexpr const char* Radiance = "Radiance";
/// The mean distance from the eye, along the camera rays, of a pixel's samples on its surface;
/// -1 where no surface is seen (finite, for colour maps). vtkOpenEXRWriter writes it as
/// OpenEXR's channel `Z` with +infinity there, vtkOpenEXRReader reads it back as this array.
constexpr const char* Depth = "Depth";
constexpr const char* RGB = "RGB";
/// vtkIlluminationField's point data for display: the radiance exposed and sRGB-encoded, bytes
/// shown as they are (Map Scalars off), as the image's RGB.
constexpr const char* DisplayRGB = "DisplayRGB";
/// vtkViewDependentRadiance's point data: the radiance toward the last eye (float RGB).
constexpr const char* ViewRadiance = "ViewRadiance";
}

#endif
