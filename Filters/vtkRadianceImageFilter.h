// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkRadianceImageFilter
 * @brief The final rendering of paper §5.3: an HDR image of the equilibrium illumination seen
 * through a pinhole camera (Documentation/Pipeline.md#rendering).
 *
 * Inputs:
 *  - port 0, the illumination: vtkLightPropagationFilter's first output, the characteristic
 *    points with point data `Radiosity` (exitant radiance, emission included), `SurfaceId` and
 *    `UVRange` (each point's patch in its surface's parameters) and optionally `TwoSided`; its
 *    field data carries the scene's cameras. When some point is non-diffuse, also the material
 *    arrays, `Normals` and `Tangents` (the hemisphere frames) and, in field data, the cover and
 *    `IncidentRadiance` (3 per entry), all of which the propagation's output carries.
 *  - port 1, the patches: vtkIntervalSubdivisionFilter's first output (exact Bezier
 *    sub-patches with `SurfaceId` and `UVRange`), whose tessellation is ray cast. Optional:
 *    left unconnected, the patches are the input of the vtkSphericalCoverFilter upstream of
 *    port 0, the patches the solution was built from (vtkCoverPatches.h: ParaView then creates
 *    the filter without asking for a second input).
 * Two ports because the illumination holds the points, not the patches' geometry; the patches
 * are what the cover was built from, so a saved solution (patches + illumination) renders new
 * views without any other stage (the walk-through case).
 *
 * Visible surface: Embree against a tessellation of the patches, refined on the exact Bezier
 * patch, so the visible point's (surface, u, v) is exact; brightness: the bilinear
 * interpolation of the characteristic points' exitant radiance around (u, v), extrapolated near
 * the edges (paper §3.4, §5.3.2); for a non-diffuse surface plus the directional part of
 * §5.3.1, the incident radiance E of the same neighbouring points reflected by the BRDF toward
 * the eye, blended with the same weights (see RadianceRenderer.h).
 *
 * Camera: CameraName selects one of the scene's cameras (position, focal point, view up, view
 * angle; the inputs' field data CameraNames / CameraParameters). With an empty CameraName (the
 * default), Position, FocalPoint, ViewUp and ViewAngle are used where the user set them, and
 * the scene's first camera where they keep their defaults, values no camera can have: the view
 * (Position and FocalPoint) while they are equal, ViewUp while (0, 0, 0), ViewAngle while 0.
 * Without a scene camera those are (0, 0, 1), (0, 0, 0), (0, 1, 0) and 30 degrees. (ParaView
 * sets every property, so "set by the user" is told by the value.) Width and Height of 0 (the
 * defaults) are the size of that scene camera (CameraName's, or the first), which must be
 * known before the inputs execute (RequestInformation announces the extent): it is read from
 * the pipeline information vtkPatchSceneReader publishes (vtkSceneCameras::SCENE_CAMERAS()); inputs
 * without it, such as a saved solution, give 512 x 512.
 *
 * Output (vtkImageData, Width x Height x 1, spacing 1, row 0 at the bottom), point data:
 * `Radiance` (float RGB, W m^-2 sr^-1, the mean over SamplesPerPixel stratified samples),
 * `Depth` (float, distance from the eye; -1 where nothing is seen), `SurfaceId` (int, -1 where
 * nothing is seen) and `RGB` (unsigned char, for display: ExposureFactor * Radiance clamped to
 * [0,1] and encoded with the sRGB transfer function).
 *
 * Pieces (vtkScenePieces.h): the whole solution is piece 0. Asked for a piece > 0 with an empty
 * input (a parallel pipeline's other pieces, the whole solution being piece 0), the filter
 * produces an empty image without a message; with a non-empty input there, it refuses with an
 * error. A piece of a solution kept in pieces (vtkPLightPropagationFilter's GatherSolution off)
 * is refused, naming GatherSolution: its cover holds some rows only (vtkPRadianceImageFilter,
 * Parallel/, renders such pieces).
 *
 * @warning Pixels are rendered in parallel (vtkSMPTools); the image does not depend on the
 * number of threads.
 */
#ifndef vtkRadianceImageFilter_h
#define vtkRadianceImageFilter_h

#include "SphericalCoverFiltersModule.h" // for export macro
#include "vtkImageAlgorithm.h"

#include <string> // for the camera name

class vtkDataSet;
class vtkPolyData;
class vtkStringArray;
namespace sphcover
{
struct Camera;
struct RenderSettings;
}

class SPHERICALCOVERFILTERS_EXPORT vtkRadianceImageFilter : public vtkImageAlgorithm
{
public:
  static vtkRadianceImageFilter* New();
  vtkTypeMacro(vtkRadianceImageFilter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The patches (vtkIntervalSubdivisionFilter's first output) on port 1.
  void SetPatchesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

  ///@{
  /**
   * Name of a camera of the scene (the illumination's field data `CameraNames`), whose pose
   * is used whatever the properties below; empty: those properties, and the scene's first
   * camera for the ones left at their defaults (see above). Default is "".
   */
  vtkSetStdStringFromCharMacro(CameraName);
  vtkGetCharFromStdStringMacro(CameraName);
  ///@}

  /**
   * The names of the scene's cameras, in the scene's order, as the inputs' pipeline information
   * announced them at the last RequestInformation (empty without a scene camera). ParaView's
   * CameraName drop-down lists them (an information property feeding a StringListDomain).
   */
  vtkStringArray* GetCameraNames() { return this->CameraNames; }

  ///@{
  /**
   * Eye position and point looked at (used without CameraName). Defaults are (0, 0, 0) and
   * (0, 0, 0): while equal, the scene's first camera's view.
   */
  vtkSetVector3Macro(Position, double);
  vtkGetVector3Macro(Position, double);
  vtkSetVector3Macro(FocalPoint, double);
  vtkGetVector3Macro(FocalPoint, double);
  ///@}

  ///@{
  /**
   * Up direction of the view (used without CameraName). Default is (0, 0, 0): the scene's
   * first camera's.
   */
  vtkSetVector3Macro(ViewUp, double);
  vtkGetVector3Macro(ViewUp, double);
  ///@}

  ///@{
  /**
   * Vertical field of view in degrees (used without CameraName). Default is 0: the scene's
   * first camera's.
   */
  vtkSetMacro(ViewAngle, double);
  vtkGetMacro(ViewAngle, double);
  ///@}

  ///@{
  /** Image size in pixels. Defaults are 0 and 0: the scene camera's size (see above). */
  vtkSetMacro(Width, int);
  vtkGetMacro(Width, int);
  vtkSetMacro(Height, int);
  vtkGetMacro(Height, int);
  ///@}

  ///@{
  /** Stratified samples per pixel, 1 to 4096. Default is 4. */
  vtkSetMacro(SamplesPerPixel, int);
  vtkGetMacro(SamplesPerPixel, int);
  ///@}

  ///@{
  /**
   * Exposure as a factor: the radiance is multiplied by it before the display mapping of `RGB`,
   * so radiance 1 / ExposureFactor shows as white (vtkIlluminationField's ExposureStops is the
   * same tone map in stops: ExposureFactor = 2^ExposureStops). A finite number > 0 (0 would
   * render black: the request fails). Default is 1.
   */
  vtkSetClampMacro(ExposureFactor, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ExposureFactor, double);
  ///@}

  ///@{
  /** Largest memory the image may take, in MiB; a larger image is refused. Default is 1024. */
  vtkSetClampMacro(MemoryLimit, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MemoryLimit, double);
  ///@}

  ///@{
  /**
   * Largest Width x Height x SamplesPerPixel (rays cast); a larger image is refused, as it
   * would take hours (sphcover::RenderSettings::MaximumSamples). Default is 1073741824 (2^30).
   */
  vtkSetClampMacro(MaximumSamples, double, 1.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumSamples, double);
  ///@}

protected:
  vtkRadianceImageFilter();
  ~vtkRadianceImageFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Width x Height, the scene camera's size where they are 0 (the inputs' information).
  void ImageSize(vtkInformationVector** inputVector, int& width, int& height) const;
  /// The one view the properties ask for: the camera (CameraName, else the pose properties)
  /// of the inputs, at ImageSize, and the renderer's settings; "" or the problem.
  std::string ViewOf(vtkInformationVector** inputVector,
    vtkPolyData* illumination,
    vtkDataSet* patches,
    sphcover::Camera& camera,
    sphcover::RenderSettings& settings);

  std::string CameraName;
  double Position[3] = { 0.0, 0.0, 0.0 };
  double FocalPoint[3] = { 0.0, 0.0, 0.0 };
  double ViewUp[3] = { 0.0, 0.0, 0.0 };
  double ViewAngle = 0.0;
  int Width = 0;
  int Height = 0;
  int SamplesPerPixel = 4;
  double ExposureFactor = 1.0;
  double MemoryLimit = 1024.0;
  double MaximumSamples = 1073741824.0;
  vtkStringArray* CameraNames;

private:
  vtkRadianceImageFilter(const vtkRadianceImageFilter&) = delete;
  void operator=(const vtkRadianceImageFilter&) = delete;
};

#endif
