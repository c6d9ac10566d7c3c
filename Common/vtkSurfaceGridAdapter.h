// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSurfaceGridAdapter
 * @brief Reads the surfaces of a dataset back into a Core scene: the input side of every
 * stage of the method.
 *
 * Accepts what vtkPatchSceneReader writes and, more generally, any dataset of
 * `VTK_BEZIER_QUADRILATERAL` (degrees from `HigherOrderDegrees`, or square degrees from the
 * point count), `VTK_QUAD` and `VTK_TRIANGLE` cells. Materials come from the cell arrays
 * `MaterialId`, `MaterialType`, `Diffuse`, `Specular`, `PhongExponent`, `Emission`; when the
 * input carries none of them and defaults are allowed, every surface gets a white diffuse
 * material (reflectance 0.8).
 */
#ifndef vtkSurfaceGridAdapter_h
#define vtkSurfaceGridAdapter_h

#include "SphericalCoverCommonModule.h" // for export macro

#include <glm/vec3.hpp>

#include <string>
#include <vector>

class vtkDataSet;
namespace sphcover
{
struct Patch;
struct Scene;
}

class SPHERICALCOVERCOMMON_EXPORT vtkSurfaceGridAdapter
{
public:
  /// False with a message in `error` when the input cannot be used (unsupported cell type,
  /// inconsistent arrays, missing material arrays when defaults are not allowed, ...).
  static bool ToScene(vtkDataSet* input,
    bool allowDefaultMaterials,
    sphcover::Scene& scene,
    std::string& error);

  /// The patches of a subdivided environment (vtkIntervalSubdivisionFilter's first output, or
  /// any surface dataset: then one patch per surface), one per cell, with their `UVRange`,
  /// `Level` and `SurfaceId` (the surface they are part of: Patch::SurfaceIndex) where the
  /// input has them. `scene` gets one surface per cell (the cell's geometry and material), so
  /// scene.Surfaces[k] belongs to patch k, whatever its SurfaceIndex.
  static bool ToPatches(vtkDataSet* input,
    sphcover::Scene& scene,
    std::vector<sphcover::Patch>& patches,
    std::string& error);

  /// After ToPatches: per surface index (Patch::SurfaceIndex) the transmittance of its material
  /// (a thin pane, paper §5.4; zero: opaque), from the cell of each of its patches.
  static std::vector<glm::dvec3> TransmittanceOfSurfaces(const sphcover::Scene& scene,
    const std::vector<sphcover::Patch>& patches);
};

#endif
