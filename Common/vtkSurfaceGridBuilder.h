// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSurfaceGridBuilder
 * @brief Turns a Core scene into the reader output of Documentation/Pipeline.md#reader.
 *
 * One cell per surface: `VTK_BEZIER_QUADRILATERAL` with the `HigherOrderDegrees` cell array
 * and VTK's point ordering for higher-order quadrilaterals (corners, edges in increasing
 * parameter, then the interior u fastest), `VTK_QUAD` for bilinear patches and `VTK_TRIANGLE`
 * for mesh triangles, so ParaView draws the exact curved surfaces. Cell data carry the
 * surface and material ids and the reflectances; field data the names, cameras and settings.
 */
#ifndef vtkSurfaceGridBuilder_h
#define vtkSurfaceGridBuilder_h

#include "SphericalCoverCommonModule.h" // for export macro

#include <vector> // for std::vector

class vtkPolyData;
class vtkUnstructuredGrid;
namespace sphcover
{
struct Patch;
struct Scene;
class BezierPatch;
}

class SPHERICALCOVERCOMMON_EXPORT vtkSurfaceGridBuilder
{
public:
  /// Replaces the contents of `output` with the scene's surfaces: cells, point data (the
  /// TextureCoordinates), cell data (SurfaceId and the material arrays) and field data.
  static void Build(const sphcover::Scene& scene, vtkUnstructuredGrid* output);

  /// Replaces the points and cells of `output` with one cell per patch (with the
  /// HigherOrderDegrees cell array). A bilinear patch with P(1,1) = P(0,1) is a triangle.
  static void BuildCells(const std::vector<const sphcover::BezierPatch*>& patches,
    vtkUnstructuredGrid* output);

  /// Sets the point array TextureCoordinates, the active TCoords, of cells that BuildCells made
  /// of whole surfaces: each control point's (i / m, j / n), a triangle's corners (0, 0),
  /// (1, 0), (1, 1) (paper §5.4: a texture over the surface's parameter square).
  static void AddTextureCoordinates(const std::vector<const sphcover::BezierPatch*>& patches,
    vtkUnstructuredGrid* output);

  /// Adds the cell arrays SurfaceNameId, MaterialId, MaterialType, TwoSided, Emission, Diffuse,
  /// Specular, PhongExponent and Transmittance of the surface each cell belongs to.
  static void AddMaterialArrays(const sphcover::Scene& scene,
    const std::vector<int>& surfaceOfCell,
    vtkUnstructuredGrid* output);

  /// Adds the field data: surface and material names, cameras, settings, source file and the
  /// scene's fingerprint (sphcover::Fingerprint).
  static void AddFieldData(const sphcover::Scene& scene, vtkUnstructuredGrid* output);

  /// Replaces the contents of `output` with the characteristic points of the patches (paper
  /// §3.2): one vertex per patch at its parametric centre, with the point data `PatchId` (the
  /// patch's index) and `Area`. The stages add their own arrays.
  static void BuildCharacteristicPoints(const std::vector<sphcover::Patch>& patches,
    vtkPolyData* output);

  /// True for the bilinear patch (P00, P10, P11, P01 = P11) that stores a triangle.
  static bool IsTriangle(const sphcover::BezierPatch& patch);

  /// Index in VTK's Bezier quadrilateral point list of control point P_ij of a patch of
  /// degree (degreeU, degreeV).
  static int VTKPointIndex(int i, int j, int degreeU, int degreeV);
};

#endif
