// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkSceneSettingsArray
 * @brief The scene file's settings block as the pipeline carries it: the field array
 * `SceneSettings` (4 named components: theta_bins, phi_bins, max_level, tolerance), written by
 * the reader and carried forward by every stage, read by the filters whose properties default
 * to "the scene's" and by the command line's budget checks.
 */
#ifndef vtkSceneSettingsArray_h
#define vtkSceneSettingsArray_h

#include "SphericalCoverCommonModule.h" // for export macro

#include "scene/Scene.h"

#include <vtkSmartPointer.h> // for vtkSmartPointer

class vtkDoubleArray;
class vtkFieldData;

class SPHERICALCOVERCOMMON_EXPORT vtkSceneSettingsArray
{
public:
  /// The `SceneSettings` array of `settings`.
  static vtkSmartPointer<vtkDoubleArray> New(const sphcover::SceneSettings& settings);

  /// The settings `fd` carries, or the scene file's defaults where it carries none (no array,
  /// or not one tuple of 4 components; `fd` may be null).
  static sphcover::SceneSettings Read(vtkFieldData* fd);
};

#endif
