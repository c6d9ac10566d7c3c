// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkIlluminationAdapter
 * @brief Reads the illuminated characteristic points (vtkLightPropagationFilter's first
 * output) into what the interpolation of paper §3.4 / §5.3.2 needs: each point's surface, its
 * patch's rectangle in the surface's parameters and its exitant radiance; shared by the
 * rendering filters (vtkRadianceImageFilter, vtkIlluminationField). When some point is
 * non-diffuse it also reads what the directional part of paper §5.3.1 needs: the cover and its
 * `IncidentRadiance` (field data), the points' frames (`Normals`, `Tangents`) and materials.
 * The materials are rebuilt from the point arrays as the propagation filter rebuilds them
 * (ReadMaterials, used by both).
 */
#ifndef vtkIlluminationAdapter_h
#define vtkIlluminationAdapter_h

#include "SphericalCoverCommonModule.h" // for export macro

#include "cover/HemisphereGrid.h"                        // for the frames
#include "render/RadianceRenderer.h"                     // for DirectionalIllumination
#include "scene/Material.h"                              // for the materials
#include "subdivision/CharacteristicPointInterpolator.h" // for the interpolator

#include <glm/vec3.hpp> // for the radiance

#include <memory> // for the directional part
#include <string> // for the error
#include <vector> // for the arrays

class vtkPolyData;

class SPHERICALCOVERCOMMON_EXPORT vtkIlluminationAdapter
{
public:
  /// The illumination of the characteristic points, ready to interpolate.
  struct Illumination
  {
    sphcover::CharacteristicPointInterpolator Interpolator;
    /// Exitant radiance (Radiosity: diffuse part plus emission) of every point.
    std::vector<glm::dvec3> ExitantRadiance;
    /// Per surface index: whether it is one side of a two-sided surface (`TwoSided`; the eye
    /// rays pass its back side, the other side's front).
    std::vector<bool> TwoSidedSurface;
    /// The directional part of paper §5.3.1 (null when every point is diffuse).
    std::unique_ptr<sphcover::DirectionalIllumination> Directional;
    /// The lamps' direct light: the irradiance on the nodes of every point's patch
    /// (`DirectIrradiance`) and every point's diffuse reflectance (`Diffuse`); empty without
    /// `DirectIrradiance`.
    sphcover::DirectLight Direct;
    /// Per surface index, its texture (paper §5.4; empty when no material is textured). The
    /// ExitantRadiance of a textured surface's points is then its untextured value,
    /// Le + k_d / pi E from `Irradiance` with the material's own k_d, as
    /// RadianceRenderer::SetSurfaceTextures asks.
    std::vector<sphcover::SurfaceTexture> Textures;
  };

  /// False with a message in `error` (one sentence naming what is missing) when the points
  /// lack Radiosity (3), SurfaceId or UVRange (4), or a rectangle is invalid, or, when
  /// `directional` is set and some point is non-diffuse, the cover, IncidentRadiance (3 per
  /// entry), Normals and Tangents. Without `directional` (a view-independent use such as
  /// vtkIlluminationField) Illumination::Directional stays null. A piece of a solution kept in
  /// pieces (vtkSolutionPieces) is refused unless `piece` accepts one: its cover holds some
  /// rows only (RadianceRenderer::DirectionalValues of its own points).
  static bool Read(vtkPolyData* points,
    Illumination& illumination,
    std::string& error,
    bool directional = true,
    bool piece = false);

  /// The material of every point from `Diffuse`, `Emission` (3 each), `MaterialType`,
  /// `Specular`, `PhongExponent`, `MaterialId` and the field arrays `MaterialNames`,
  /// `MaterialFiles` (tabulated BRDFs); a missing MaterialType means diffuse. False with one
  /// sentence in `error` for missing arrays, an unknown type or a tabulated material without a
  /// table file.
  static bool ReadMaterials(vtkPolyData* points,
    std::vector<sphcover::Material>& materials,
    std::string& error);

  /// Gives every point of a textured material the texture's mean over its patch (`UVRange`)
  /// times the material's diffuse reflectance (sphcover::MaterialOverPatch): the propagation's
  /// reflectance of the point (paper §5.4). False with one sentence in `error` without UVRange.
  static bool ApplyTextureMeans(vtkPolyData* points,
    std::vector<sphcover::Material>& materials,
    std::string& error);

  /// The hemisphere frame of every point from its position, `Normals` and `Tangents` (the
  /// cover's frames); false (and no frames) when those arrays are missing.
  static bool ReadFrames(vtkPolyData* points, std::vector<sphcover::HemisphereFrame>& frames);

private:
  /// Fills Illumination::Direct when the points have `DirectIrradiance`: 3 n^2
  /// components for an odd n from 3 to 33, finite and not negative, with `Diffuse` (3).
  static bool ReadDirectIrradiance(vtkPolyData* points,
    Illumination& illumination,
    std::string& error);
  /// Fills Illumination::Textures and the untextured exitant radiance of textured points when
  /// the field data names a texture (MaterialTextures); needs `Irradiance` (3) then.
  static bool ReadTextures(vtkPolyData* points, Illumination& illumination, std::string& error);
  /// Fills Illumination::Directional when some point is non-diffuse.
  static bool ReadDirectional(vtkPolyData* points,
    Illumination& illumination,
    std::string& error,
    bool piece);
};

#endif
