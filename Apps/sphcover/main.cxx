// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file main.cxx
 * @brief `sphcover`: the command-line program (README.md#command-line): its options and the
 * dispatch to the commands (Commands.h), which run the VTK pipeline and format what it gives.
 *
 *   sphcover --version
 *   sphcover info SCENE
 *   sphcover subdivide SCENE -o patches.vtm [--range-method bernstein|natural] [--set k=v]...
 *   sphcover solve SCENE [-o solution.vtm] [--report report.json] [--fill projection|raycasting]
 *                  [--lamps measured|cells] [--hemispheres interpolated|computed]
 *                  [--direct-nodes N] [--bounce-rays N] [--direct-tolerance F]
 *   sphcover render SCENE [-o out.exr|out.png] [--png out.png] [--camera NAME] [--size WxH]
 *                   [--spp N] [--exposure E] [--solution solution.vtm] [--report report.json]
 *                   [--set k=v]
 *   sphcover walk SOLUTION (--path PATH.json | --orbit N) -o FOLDER [--size WxH] [--exr]
 *                 [--spp N] [--exposure E] [--report report.json]
 *
 * Every error is one line on stderr and a non-zero exit status; no output file is left
 * half-written, also when interrupted (OutputFiles.h).
 *
 * Under mpiexec (README.md#running-on-a-cluster) the program joins MPI: every rank reads and
 * subdivides alike, the spherical cover's rows are built on all ranks and gathered on rank 0
 * (vtkSphericalCoverFilter, Controller), which deals each rank its rows of the propagation
 * (vtkLightPropagationFilter); only rank 0 prints, writes files and renders. Started any other
 * way it is a plain program and never touches MPI.
 */
#include "Commands.h"
#include "ErrorCollector.h"
#include "Options.h"
#include "OutputFiles.h"
#include "SphcoverVersion.h"

#include <CLI/CLI.hpp>
#include <vtkLogger.h>
#include <vtkMPIController.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkSMPTools.h>
#include <vtkStringOutputWindow.h>

#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

namespace
{
/// Whether an MPI launcher started this process: Open MPI's mpiexec sets OMPI_COMM_WORLD_SIZE,
/// MPICH's and PMIx launchers PMI_SIZE or PMIX_RANK. Only then is MPI initialised, so that the
/// program started by hand needs no MPI runtime.
bool LaunchedByMpiexec()
{
  for (const char* variable : { "OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK" })
  {
    if (std::getenv(variable))
    {
      return true;
    }
  }
  return false;
}

/// The options of an image's samples and tone, the same for render and walk; `budgetHelp`
/// says what --max-samples bounds.
void AddImageOptions(CLI::App* command,
  sphcover_cli::Options& options,
  const std::string& budgetHelp)
{
  command->add_option("--spp", options.SamplesPerPixel, "Samples per pixel (default 4)")
    ->check(CLI::Range(1, 4096));
  command->add_option("--exposure",
    options.ExposureFactor,
    "Factor (not stops) the radiance is multiplied by before tone mapping, > 0 (default 1)");
  command->add_option("--max-samples", options.MaxSamples, budgetHelp)
    ->check(CLI::Range(1.0, 1e18));
}

/// The options of the cover's fill and of the light it measures, the same for solve and render.
void AddCoverOptions(CLI::App* command, sphcover_cli::Options& options)
{
  command->add_option("--fill", options.Fill, "R-buffer fill: raycasting (default) or projection")
    ->check(CLI::IsMember({ "projection", "raycasting" }));
  command
    ->add_option("--lamps",
      options.Lamps,
      "How the cover measures a lamp's regions: measured (default: integrated over the lamp "
      "with shadow rays, ray fill only) or cells (the paper's: counted in cells)")
    ->check(CLI::IsMember({ "cells", "measured" }));
  command
    ->add_option("--hemispheres",
      options.Hemispheres,
      "computed (default: every hemisphere cast) or interpolated (a point between two "
      "neighbours on a flat surface gets its hemisphere from theirs, paper 3.4, rays only where "
      "they disagree)")
    ->check(CLI::IsMember({ "interpolated", "computed" }));
  command
    ->add_option("--direct-nodes",
      options.DirectNodes,
      "Nodes per patch side at which the lamps' direct light is computed and interpolated "
      "(odd, 3 to 33; default 9); 0: none, all light interpolated between the characteristic "
      "points (the paper's)")
    ->check(CLI::IsMember({ 0, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31, 33 }));
  command
    ->add_option("--bounce-rays",
      options.BounceRays,
      "Rays per side (N x N) gathering the first bounce of the lamps' direct light at every "
      "node of --direct-nodes (0 to 256; default 32); 0: the direct light only")
    ->check(CLI::Range(0, 256));
  command
    ->add_option("--direct-tolerance",
      options.DirectTolerance,
      "Nodes beyond a patch's 3 x 3 are computed where its 3 x 3 direct light departs from "
      "bilinear by more than this fraction of the brighter of the patch and the scene (a "
      "shadow's edge crosses it), else interpolated (0 to 1; default 0.05); 0: at every patch")
    ->check(CLI::Range(0.0, 1.0));
}
}

int main(int argc, char** argv)
{
  CLI::App app{ "sphcover: view-independent global illumination of Bezier-patch scenes by the "
                "spherical cover of Mudur and Pattanaik (1990)" };
  app.require_subcommand(1);
  // CLI11 handles the flag before the subcommand requirement: prints, exits 0.
  app.set_version_flag("--version",
    "sphcover " SPHCOVER_VERSION "\n"
    "built with VTK " SPHCOVER_VTK_VERSION ", Embree " SPHCOVER_EMBREE_VERSION
    ", OpenEXR " SPHCOVER_OPENEXR_VERSION,
    "Print the version of sphcover and of the VTK, Embree and OpenEXR it was built with");
  // Global options may also follow the subcommand: `sphcover info X --threads 2`.
  app.fallthrough();
  sphcover_cli::Options options;
  app
    .add_option(
      "--threads", options.Threads, "Worker threads for the parallel stages (0: one per core)")
    ->check(CLI::Range(0, 4096));
  app.add_flag(
    "--quiet,-q", options.Quiet, "No progress on stderr (bars on a terminal, lines elsewhere)");
  app
    .add_option("--memory-limit",
      options.MemoryLimit,
      "Memory budget of each stage in MiB (default 8192): the subdivision's patches, the cover "
      "(R-buffers per thread and its arrays), the propagation and the image are estimated "
      "before allocating and refused beyond it")
    ->check(CLI::PositiveNumber);
  app
    .add_option("--max-patches",
      options.MaxPatches,
      "Budget of patches (default 1000000): the subdivision stops with an error beyond it")
    ->check(CLI::Range(1, 2147483647));
  app
    .add_option("--max-pair-tests",
      options.MaxPairTests,
      "Budget of the subdivision's pair tests, its time (default 1e9: 10 to 25 minutes on two "
      "threads): a sweep predicted to exceed it is refused")
    ->check(CLI::Range(1.0, 1e18));

  CLI::App* info = app.add_subcommand("info",
    "Print a scene's summary: surfaces, patch degrees, "
    "materials, cameras, bounds and settings");
  info->add_option("SCENE", options.Scene, "A .scene or .bpt file")->required();

  CLI::App* subdivide = app.add_subcommand("subdivide",
    "Subdivide a scene into patches and characteristic points (paper section 4) and write both "
    "as a VTK multiblock file (.vtm) for inspection in ParaView");
  subdivide->add_option("SCENE", options.Scene, "A .scene or .bpt file")->required();
  subdivide->add_option("-o,--output", options.Output, "Output file (.vtm)")->required();
  subdivide->add_option("--range-method", options.RangeMethod, "bernstein (default) or natural")
    ->check(CLI::IsMember({ "bernstein", "natural" }));
  subdivide->add_option("--set",
    options.Settings,
    "Override a setting of the scene file, e.g. --set max_level=3 (theta_bins, phi_bins, "
    "max_level, tolerance, min_patch_size)");

  CLI::App* solve = app.add_subcommand("solve",
    "Run the method up to equilibrium (subdivision, spherical cover, light propagation) and "
    "write the solution and a JSON report (surfaces' mean irradiance and exitant radiance, form "
    "factors between named surfaces, energy balance, counts, timings)");
  solve->add_option("SCENE", options.Scene, "A .scene or .bpt file")->required();
  solve->add_option("-o,--output", options.Output, "Solution file (.vtm): patches and cover");
  solve->add_option("--report", options.Report, "Report file (.json)");
  AddCoverOptions(solve, options);
  solve->add_option("--range-method", options.RangeMethod, "bernstein (default) or natural")
    ->check(CLI::IsMember({ "bernstein", "natural" }));
  solve->add_option(
    "--set", options.Settings, "Override a setting of the scene file (see subdivide)");

  CLI::App* render = app.add_subcommand("render",
    "Run the whole method (or load a saved solution) and render the scene through a camera "
    "(paper section 5.3): an HDR radiance image, written tone-mapped as PNG");
  render
    ->add_option("SCENE", options.Scene, "A .scene file (its cameras; solved unless --solution)")
    ->required();
  render->add_option("-o,--output",
    options.Output,
    "Image file: .exr (HDR Radiance as R, G, B and the depth as Z, float; Z is +inf where no "
    "surface is seen) or .png (tone-mapped sRGB)");
  render->add_option("--png", options.Png, "PNG file (tone-mapped sRGB)");
  render->add_option("--camera", options.Camera, "Camera of the scene (default: the first)");
  render->add_option("--size", options.Size, "Image size WIDTHxHEIGHT (default: the camera's)");
  AddImageOptions(render,
    options,
    "Budget of width x height x spp rays (default 2^30, about 18 minutes on one core); a "
    "larger image is refused before solving");
  render->add_option("--solution",
    options.SolutionFile,
    "A solution written by `sphcover solve -o` (.vtm): only render, no solving");
  render->add_option("--report", options.Report, "Report file (.json), with timings_s.render");
  AddCoverOptions(render, options);
  render->add_option(
    "--set", options.Settings, "Override a setting of the scene file (see subdivide)");

  CLI::App* walk = app.add_subcommand("walk",
    "Walk through a saved solution: render every camera of a path (paper section 5.3) into "
    "FOLDER/frame_0000.png, frame_0001.png, ..., reading the solution once, and print the "
    "milliseconds per frame");
  walk
    ->add_option(
      "SOLUTION", options.SolutionFile, "A solution written by `sphcover solve -o` (.vtm)")
    ->required();
  CLI::Option* pathOption = walk->add_option("--path",
    options.PathFile,
    "Camera path (.json): {\"cameras\": [...]}, each camera in the scene format's keys "
    "(position, focal_point, view_up, view_angle, width, height; name optional)");
  walk
    ->add_option("--orbit",
      options.Orbit,
      "Instead of --path: N cameras on a circle around the scene from its first camera (about "
      "the axis along its view up through the point of its view axis nearest the scene's "
      "centre; the first is the camera itself)")
    ->check(CLI::Range(1, 1000000))
    ->excludes(pathOption);
  walk->add_option("-o,--output", options.Output, "Folder of the frames (created if missing)")
    ->required();
  walk->add_option(
    "--size", options.Size, "Frame size WIDTHxHEIGHT of every camera (default: each camera's)");
  walk->add_flag("--exr", options.Exr, "Also write frame_NNNN.exr (HDR Radiance and depth)");
  AddImageOptions(walk, options, "Budget of width x height x spp rays of a frame (default 2^30)");
  walk->add_option("--report", options.Report, "Report file (.json): milliseconds of each frame");

  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    return app.exit(e);
  }

  // MPI before any filter exists: the cover filter takes the global controller when it is made.
  vtkSmartPointer<vtkMPIController> mpi;
  if (LaunchedByMpiexec())
  {
    mpi = vtkSmartPointer<vtkMPIController>::New();
    mpi->Initialize(&argc, &argv);
    vtkMultiProcessController::SetGlobalController(mpi);
    options.Rank = mpi->GetLocalProcessId();
    options.Ranks = mpi->GetNumberOfProcesses();
    // One progress display, rank 0's: the ranks build their rows at about the same pace.
    options.Quiet = options.Quiet || options.Rank > 0;
  }

  // Before any thread starts: an interrupted run leaves no partial output behind.
  sphcover_cli::WatchTerminationSignals();

  // ParaView's VTK selects the Sequential SMP backend unless told otherwise (README.md#layout).
  vtkSMPTools::SetBackend("STDThread");
  vtkSMPTools::Initialize(options.Threads);

  // Errors of VTK objects nobody observes (the XML parser inside a reader) would print
  // VTK's multi-line blocks next to the one error the command gives: keep their text, and show
  // it only when the command succeeds (then it is a warning worth seeing).
  vtkNew<vtkStringOutputWindow> vtkMessages;
  vtkOutputWindow::SetInstance(vtkMessages);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  int status = 0;
  try
  {
    // Only solve and render build a cover, the stage the ranks share, and render and walk
    // render a solution kept in pieces on the ranks that hold them; the other commands run on
    // rank 0 alone.
    if (options.Rank > 0 && !solve->parsed() && !render->parsed() && !walk->parsed())
    {
    }
    else if (info->parsed())
    {
      status = sphcover_cli::RunInfo(options);
    }
    else if (subdivide->parsed())
    {
      status = sphcover_cli::RunSubdivide(options);
    }
    else if (solve->parsed())
    {
      status = sphcover_cli::RunSolve(options);
    }
    else if (render->parsed())
    {
      status = sphcover_cli::RunRender(options);
    }
    else if (walk->parsed())
    {
      status = sphcover_cli::RunWalk(options);
    }
  }
  catch (const std::exception& e)
  {
    // Every rank fails alike (the same input, or the cover's agreed error): rank 0 says it.
    if (options.Rank == 0)
    {
      std::cerr << "sphcover: error: " << e.what() << std::endl;
    }
    status = 1;
  }
  const std::string messages = vtkMessages->GetOutput();
  if (status == 0 && !messages.empty() && options.Rank == 0)
  {
    std::cerr << messages << std::flush;
  }
  // The stages' own warnings, one line each (ErrorCollector).
  for (const std::string& warning : ErrorCollector::Warnings())
  {
    if (status == 0 && options.Rank == 0)
    {
      std::cerr << "sphcover: warning: " << warning << std::endl;
    }
  }
  vtkOutputWindow::SetInstance(nullptr);
  if (mpi)
  {
    vtkMultiProcessController::SetGlobalController(nullptr);
    mpi->Finalize();
  }
  return status;
}
