// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPatchSceneReader
 * @brief Reads a `.scene` file (Data/scenes/FORMAT.md): the surfaces of the environment as exact
 * curved patches, their materials, cameras and solver settings.
 *
 * Output (Documentation/Pipeline.md#reader): a vtkUnstructuredGrid with one cell per surface S_i of
 * paper §4.3, `VTK_BEZIER_QUADRILATERAL` (with the `HigherOrderDegrees` cell array), `VTK_QUAD` for
 * bilinear patches, `VTK_TRIANGLE` for mesh triangles. Cell data: `SurfaceId`,
 * `SurfaceNameId`, `MaterialId`, `MaterialType`, `Emission` (3), `Diffuse` (3), `Specular` (3),
 * `PhongExponent`, `TwoSided`. Field data: `SurfaceNames`, `MaterialNames`,
 * `MaterialTypeNames`, `MaterialFiles`, `CameraNames`, `CameraParameters` (12 named
 * components), `SceneSettings` (5 named components: theta_bins, phi_bins, max_level, tolerance,
 * min_patch_size), `SourceFile`, `SceneFingerprint` (one string, sphcover::Fingerprint: the stages
 * pass it on, so a saved solution names its scene).
 *
 * A file with a `.bpt` extension is read as a .bpt file on its own (see vtkBPTReader).
 * Bad input gives one error naming the file, the location (line or JSON pointer) and the
 * problem, and an empty output with a failed request.
 *
 * Pipeline information: the scene's cameras (CameraNames, CameraParameters) under the key
 * vtkSceneCameras::SCENE_CAMERAS(), which passes downstream before any data
 * exists, so that vtkRadianceImageFilter knows a camera's image size when it announces its
 * extent. RequestInformation therefore loads the file (on every process; a file that does not
 * load publishes nothing there, and RequestData reports the error), and the RequestData that
 * follows builds from that load unless the file was modified in between: one read per update.
 *
 * Pieces (vtkScenePieces.h): global illumination needs the whole scene in one place, so the
 * reader gives the whole scene to piece 0 and an empty grid, without building it, to every
 * other piece (under `mpiexec -n N pvbatch --symmetric` only rank 0 builds the surfaces).
 */
#ifndef vtkPatchSceneReader_h
#define vtkPatchSceneReader_h

#include "SphericalCoverReadersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string

namespace sphcover
{
struct Scene;
}

class SPHERICALCOVERREADERS_EXPORT vtkPatchSceneReader : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkPatchSceneReader* New();
  vtkTypeMacro(vtkPatchSceneReader, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to read. Relative paths inside a scene resolve against its folder. Default is
   * empty.
   */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

protected:
  vtkPatchSceneReader();
  ~vtkPatchSceneReader() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /// Reads the file into a Core scene; throws sphcover::InputError.
  virtual sphcover::Scene LoadFile(const std::string& fileName);

  std::string FileName;

private:
  /// The scene RequestInformation loaded, kept for the RequestData that follows so that the
  /// file is read once per update (with the file's modification time it was read at).
  struct LoadedScene;
  std::unique_ptr<LoadedScene> Loaded;

  vtkPatchSceneReader(const vtkPatchSceneReader&) = delete;
  void operator=(const vtkPatchSceneReader&) = delete;
};

#endif
