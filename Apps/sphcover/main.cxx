// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file main.cxx
 * @brief `sphcover`: the command-line program (SPEC §5).
 *
 * Every error is one line on stderr and a non-zero exit status.
 */
#include "SceneSummary.h"
#include "vtkSceneFileLoader.h"

#include "InputError.h"
#include "Scene.h"

#include <CLI/CLI.hpp>
#include <vtkSMPTools.h>

#include <exception>
#include <iostream>

namespace
{
int RunInfo(const std::string& sceneFile)
{
  const sphcover::Scene scene = vtkSceneFileLoader::Load(sceneFile);
  sphcover::PrintSceneSummary(scene, std::cout);
  return 0;
}
}

int main(int argc, char** argv)
{
  CLI::App app{ "sphcover: view-independent global illumination of Bezier-patch scenes by the "
                "spherical cover of Mudur and Pattanaik (1990)" };
  app.require_subcommand(1);
  // Global options may also follow the subcommand: `sphcover info X --threads 2`.
  app.fallthrough();
  int threads = 0;
  app.add_option("--threads", threads, "Worker threads for the parallel stages (0: one per core)")
    ->check(CLI::Range(0, 4096));

  std::string sceneFile;
  CLI::App* info = app.add_subcommand("info", "Print a scene's summary: surfaces, patch degrees, "
                                              "materials, cameras, bounds and settings");
  info->add_option("SCENE", sceneFile, "A .scene or .bpt file")->required();

  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    return app.exit(e);
  }

  // ParaView's VTK selects the Sequential SMP backend unless told otherwise (SPEC §2).
  vtkSMPTools::SetBackend("STDThread");
  vtkSMPTools::Initialize(threads);

  try
  {
    if (info->parsed())
    {
      return RunInfo(sceneFile);
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "sphcover: error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
