// SPDX-License-Identifier: BSD-3-Clause
// sphcover info SCENE: the scene's summary (SceneSummary.h), from Core's scene.
#include "Commands.h"
#include "Options.h"
#include "SceneSummary.h"

#include "vtkSceneFileLoader.h"

#include "scene/Scene.h"

#include <iostream>

namespace sphcover_cli
{
int RunInfo(const Options& options)
{
  const sphcover::Scene scene = vtkSceneFileLoader::Load(options.Scene);
  sphcover::PrintSceneSummary(scene, std::cout);
  return 0;
}
}
