// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SceneCamera.h
 * @brief The camera `sphcover render` looks through: --camera or the scene's first, from the
 * reader's field data (CameraNames, CameraParameters), as vtkRadianceImageFilter reads them.
 */
#ifndef SPHCOVER_SCENECAMERA_H
#define SPHCOVER_SCENECAMERA_H

#include "scene/Camera.h"

#include <string>

class vtkDataObject;

namespace sphcover_cli
{
/// The image size of --size, "WxH" as two positive integers; throws one line naming --size
/// otherwise.
void ParseSize(const std::string& text, int& width, int& height);

/// The camera named `name` (the first if empty) among `surfaces`' field data; throws one line
/// naming `scene` and the cameras it has when there is none of that name.
sphcover::Camera SceneCamera(vtkDataObject* surfaces,
  const std::string& name,
  const std::string& scene);
}

#endif
