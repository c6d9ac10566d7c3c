// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSolutionRenderer
 * @brief A solution's renderer of paper §5.3, built once from the pipeline's datasets and used
 * for any number of views: after the solve every view is cheap (paper §1, §5.3), so a
 * walk-through (`sphcover walk`, Documentation/notes/walk-through.md) builds the ray caster and
 * the interpolation once and only traces each frame's rays.
 *
 * vtkRadianceImageFilter renders its one image through the same two functions, which is what
 * makes a walk's frame equal, bit for bit, to the filter's image of the same camera.
 */
#ifndef vtkSolutionRenderer_h
#define vtkSolutionRenderer_h

#include "SphericalCoverFiltersModule.h" // for export macro

#include "render/RadianceRenderer.h" // for the renderer and its image

#include <memory> // for the renderer
#include <string> // for the error

class vtkDataSet;
class vtkImageData;
class vtkPolyData;

class SPHERICALCOVERFILTERS_EXPORT vtkSolutionRenderer
{
public:
  /**
   * The renderer of the patches (vtkIntervalSubdivisionFilter's first output) lit by the
   * illumination (vtkLightPropagationFilter's first output, see vtkIlluminationAdapter): the
   * diffuse part interpolated between the characteristic points (§5.3.2), the lamps' direct
   * light from its nodes where the illumination has them, and the directional part of
   * non-diffuse surfaces (§5.3.1). Null with one sentence in `error` when the illumination
   * cannot be read, the patches cannot be used or the two do not come from one solution (a
   * surface of the patches without characteristic points); what the renderer's constructor
   * throws (Embree failing, a bad BRDF table) propagates. A piece of a solution kept in pieces
   * (vtkSolutionPieces) is refused unless `piece` accepts one: its renderer renders only with
   * the directional values of every rank's points (RadianceRenderer::Render with a table).
   */
  static std::unique_ptr<sphcover::RadianceRenderer> New(vtkPolyData* illumination,
    vtkDataSet* patches,
    std::string& error,
    bool piece = false);

  /**
   * The image as the pipeline's vtkImageData (Width x Height x 1, spacing 1, row 0 at the
   * bottom), point data `Radiance` (float RGB), `Depth`, `SurfaceId` and, as its scalars, `RGB`:
   * the bytes of exposureFactor x Radiance clamped to [0, 1] and sRGB-encoded (IEC 61966-2-1).
   */
  static void ToImageData(const sphcover::RenderedImage& image,
    double exposureFactor,
    vtkImageData* output);

  /// The sRGB transfer function (IEC 61966-2-1) of a linear value clamped to [0, 1], as a byte:
  /// the display mapping of `RGB` above, shared with the other displays of the radiance.
  static unsigned char EncodeSRGB(double linear);
};

#endif
