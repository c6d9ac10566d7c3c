// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkHemisphereExtractor
 * @brief One characteristic point's hemisphere H_i of the spherical cover (paper §3.3), for
 * inspection (Documentation/Pipeline.md#inspection-filters): as an image of its (theta, phi) cells
 * and as a 3-D hemisphere placed at the point.
 *
 * Input: the first output of vtkSphericalCoverFilter (or that output saved and read back): the
 * characteristic points with point data `Normals`, `Tangents`, `SurfaceId` and the cover in
 * field data (vtkSphericalCoverArrays).
 *
 * The hemisphere is row PointId of the cover matrix: paper §3.3 stores each h_ij as strips
 * "ranging from phi_1 to phi_2 in a row of the (theta, phi) cell array"; the extractor paints
 * the strips of every source of the row back into the cell array.
 *
 * Output 0 (vtkImageData): PhiBins x ThetaBins cells, x = phi and y = theta: dimensions
 * (PhiBins + 1) x (ThetaBins + 1) x 1, origin 0, spacing (2 pi / PhiBins, (pi / 2) /
 * ThetaBins, 1), so a point's coordinates are its (phi, theta) in radians and cell (column,
 * row) is the cover's cell row * PhiBins + column. Cell data:
 *  - `Source` (int): the patch seen through the cell, -1 where none;
 *  - `SurfaceId` (int): the surface of that patch, -1 where none;
 *  - `SurfaceNameId` (int, when the input has it): the named scene entry of that patch (all
 *    surfaces of one `.bpt` model share it), -1 where none;
 *  - `R` (float): the mean distance of the cell's strip to its source, NaN where none;
 *  - `ProjectedSolidAngle` (double): the cell's cosine-weighted measure
 *    dphi (cos 2 theta0 - cos 2 theta1) / 4 (Documentation/Pipeline.md#spherical-cover), whatever
 * its source: the cells sum to pi, those with a source to the point's `CoveredProjectedSolidAngle`.
 * `Radiance` (the incident radiance of each cell) is not produced yet: it will be added once the
 * light propagation stage (Documentation/Pipeline.md#light-propagation) stores incident radiance
 * with the cover; until then the extractor shows geometry only and makes up no values.
 *
 * Output 1 (vtkPolyData): the hemisphere as a 3-D mesh of radius Radius centred on the point,
 * in the point's frame: N (`Normals`, theta = 0), T (`Tangents`, phi = 0) and B = N x T
 * (phi = pi / 2), the right-handed frame (T, B, N) of sphcover::HemisphereFrame. One cell per
 * (theta, phi) cell in the same order as the image's cells, with the same cell data: the cells
 * of the first row meet at the pole and are triangles, the others quads. Point data `Normals`:
 * the outward unit directions, for smooth shading.
 *
 * Radius 0 (the default) means automatic: 5% of the diagonal of the bounding box of the input's
 * points, large enough to see and small enough to stay clear of most surfaces.
 *
 * Errors (one message, failed request): an input without a cover, PointId out of range, a
 * negative Radius, missing `Normals`/`Tangents`.
 *
 * @note The image's WHOLE_EXTENT depends on the bins of the cover, which are data: to publish it
 * in RequestInformation, as image consumers expect, the input is brought up to date there (with
 * the request of the previous pass, so it is not executed twice).
 *
 * Pieces (vtkScenePieces.h): the whole scene is piece 0. Asked for a piece > 0 with an empty
 * input (the readers' other pieces in a parallel pipeline), the filter
 * produces empty outputs without a message; with a non-empty input there, it refuses with an
 * error (a piece of the scene would give a wrong illumination). An empty input on piece 0 is an
 * error, as in serial.
 */
#ifndef vtkHemisphereExtractor_h
#define vtkHemisphereExtractor_h

#include "SphericalCoverFiltersModule.h" // for export macro
#include "vtkAlgorithm.h"

class vtkImageData;
class vtkPolyData;

class SPHERICALCOVERFILTERS_EXPORT vtkHemisphereExtractor : public vtkAlgorithm
{
public:
  static vtkHemisphereExtractor* New();
  vtkTypeMacro(vtkHemisphereExtractor, vtkAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The characteristic point (receiver) whose hemisphere is extracted. Default 0. */
  vtkSetMacro(PointId, vtkIdType);
  vtkGetMacro(PointId, vtkIdType);
  ///@}

  ///@{
  /**
   * Radius of the 3-D hemisphere (output 1), in scene units. 0 (the default): 5% of the
   * diagonal of the input points' bounding box. Negative values are an error.
   */
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  /// The automatic radius as a fraction of the bounding-box diagonal.
  static constexpr double AutomaticRadiusFraction = 0.05;

  /// Output 0: the (phi, theta) cell image.
  vtkImageData* GetImageOutput();
  /// Output 1: the 3-D hemisphere mesh.
  vtkPolyData* GetMeshOutput();

  vtkTypeBool ProcessRequest(vtkInformation* request,
    vtkInformationVector** inInfo,
    vtkInformationVector* outInfo) override;

protected:
  vtkHemisphereExtractor();
  ~vtkHemisphereExtractor() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  virtual int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*);
  virtual int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*);

  vtkIdType PointId = 0;
  double Radius = 0.0;

private:
  vtkHemisphereExtractor(const vtkHemisphereExtractor&) = delete;
  void operator=(const vtkHemisphereExtractor&) = delete;
};

#endif
