// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSceneCameras
 * @brief The scene's cameras as the pipeline carries them, for the reader that publishes them
 * and the filters and front ends that look through them.
 *
 * Data: the field arrays CameraNames (strings) and CameraParameters (12 components: position,
 * focal point, view up, view angle, width, height; vtkSphericalCoverArrayNames.h), which every
 * stage carries forward. Information: SCENE_CAMERAS(), a vtkDataObject holding those two arrays,
 * set by vtkPatchSceneReader in RequestInformation; a meta-data key, so it passes downstream
 * before any data exists (vtkRadianceImageFilter needs a camera's image size to announce its
 * extent).
 */
#ifndef vtkSceneCameras_h
#define vtkSceneCameras_h

#include "SphericalCoverCommonModule.h" // for export macro

#include "scene/Camera.h"

#include <string> // for std::string
#include <vector> // for std::vector

class vtkFieldData;
class vtkInformationDataObjectMetaDataKey;

class SPHERICALCOVERCOMMON_EXPORT vtkSceneCameras
{
public:
  /// The pipeline-information key of the scene's cameras.
  static vtkInformationDataObjectMetaDataKey* SCENE_CAMERAS();

  /// The camera named `name` (the first if `name` is empty) among `fd`'s cameras; false when
  /// `fd` has no such camera (or no cameras, or is null).
  static bool Find(vtkFieldData* fd, const std::string& name, sphcover::Camera& camera);

  /// The names of `fd`'s cameras, in the scene's order (empty when it has none).
  static std::vector<std::string> Names(vtkFieldData* fd);
};

#endif
