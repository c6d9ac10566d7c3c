// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkIlluminationAdapter
 * @brief Reads the illuminated characteristic points (vtkLightPropagationFilter's first
 * output) into what the interpolation of paper §3.4 / §5.3.2 needs: each point's surface, its
 * patch's rectangle in the surface's parameters and its exitant radiance; shared by the
 * rendering filters (vtkRadianceImageFilter, vtkIlluminationField).
 */
#ifndef vtkIlluminationAdapter_h
#define vtkIlluminationAdapter_h

#include "SphericalCoverFiltersModule.h" // for export macro

#include "CharacteristicPointInterpolator.h" // for the interpolator

#include <glm/vec3.hpp> // for the radiance

#include <string> // for the error
#include <vector> // for the arrays

class vtkPolyData;

class SPHERICALCOVERFILTERS_EXPORT vtkIlluminationAdapter
{
public:
  /// The illumination of the characteristic points, ready to interpolate.
  struct Illumination
  {
    sphcover::CharacteristicPointInterpolator Interpolator;
    /// Exitant radiance (Radiosity: diffuse part plus emission) of every point.
    std::vector<glm::dvec3> ExitantRadiance;
    /// Per surface index: whether its back side shows its radiance too (`TwoSided`).
    std::vector<bool> TwoSidedSurface;
  };

  /// False with a message in `error` (one sentence naming what is missing) when the points
  /// lack Radiosity (3), SurfaceId or UVRange (4), or a rectangle is invalid.
  static bool Read(vtkPolyData* points, Illumination& illumination, std::string& error);
};

#endif
