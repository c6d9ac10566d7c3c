// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSurfaceGridBuilder
 * @brief Turns a Core scene into the reader output of SPEC §4.1.
 *
 * One cell per surface: `VTK_BEZIER_QUADRILATERAL` with the `HigherOrderDegrees` cell array
 * and VTK's point ordering for higher-order quadrilaterals (corners, edges in increasing
 * parameter, then the interior u fastest), `VTK_QUAD` for bilinear patches and `VTK_TRIANGLE`
 * for mesh triangles, so ParaView draws the exact curved surfaces. Cell data carry the
 * surface and material ids and the reflectances; field data the names, cameras and settings.
 */
#ifndef vtkSurfaceGridBuilder_h
#define vtkSurfaceGridBuilder_h

#include "SphericalCoverReadersModule.h" // for export macro

class vtkUnstructuredGrid;
namespace sphcover
{
struct Scene;
class BezierPatch;
}

class SPHERICALCOVERREADERS_EXPORT vtkSurfaceGridBuilder
{
public:
  /// Replaces the contents of `output` with the scene's surfaces.
  static void Build(const sphcover::Scene& scene, vtkUnstructuredGrid* output);

  /// Index in VTK's Bezier quadrilateral point list of control point P_ij of a patch of
  /// degree (degreeU, degreeV).
  static int VTKPointIndex(int i, int j, int degreeU, int degreeV);
};

#endif
