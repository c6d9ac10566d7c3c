// SPDX-License-Identifier: BSD-3-Clause
// sphcover walk SOLUTION: a walk-through of a saved solution, the image of paper §5.3 through
// every camera of a path, one frame each. The paper's point (§1, §5.3): after the solve every
// view is cheap, mirrors and glossy surfaces included, so the solution is read and its renderer
// built once (vtkSolutionRenderer) and each frame only casts its rays.
#include "Budgets.h"
#include "Commands.h"
#include "Options.h"
#include "OutputFiles.h"
#include "Pipeline.h"
#include "ProgressBar.h"
#include "SavedSolution.h"
#include "SceneCamera.h"
#include "vtkRankRenderer.h"

#include "vtkCoverDistribution.h"
#include "vtkSMPParallelFor.h"
#include "vtkSolutionRenderer.h"

#include "scene/CameraPath.h"

#include <vtkDataSet.h>
#include <vtkImageData.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace fs = std::filesystem;

namespace sphcover_cli
{
namespace
{
/// The frames' folder, checked before any work: an existing folder this process may write to,
/// or a new one whose parent folder exists and is writable (it is created before the first
/// frame, after the path and the solution have been read).
void CheckFrameFolder(const std::string& folder)
{
  if (folder.empty())
  {
    throw std::runtime_error("no output: give -o FOLDER for the frames");
  }
  std::error_code error;
  const fs::path path(folder);
  if (fs::exists(path, error))
  {
    if (!fs::is_directory(path, error))
    {
      throw std::runtime_error("-o '" + folder + "': not a folder (the frames' folder)");
    }
    if (access(path.c_str(), W_OK) != 0)
    {
      throw std::runtime_error("cannot write into '" + folder + "': " + std::strerror(errno));
    }
    return;
  }
  const fs::path parent =
    path.has_parent_path() && !path.parent_path().empty() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, error) || access(parent.c_str(), W_OK) != 0)
  {
    throw std::runtime_error("cannot create '" + folder + "': folder " + parent.string() +
      (fs::is_directory(parent, error) ? ": " + std::string(std::strerror(errno))
                                       : " does not exist"));
  }
}

/// frame_0000, frame_0001, ...: at least four digits, more for a path of more than 10000
/// cameras, so that the names sort in the path's order (and ffmpeg's frame_%04d reads them).
std::string FrameStem(std::size_t index, std::size_t count)
{
  int digits = 4;
  for (std::size_t limit = 10000; limit < count; limit *= 10)
  {
    ++digits;
  }
  std::ostringstream name;
  name << "frame_" << std::setw(digits) << std::setfill('0') << index;
  return name.str();
}

/// The cameras of the walk: --path's (its mistakes located in the file) or --orbit's around
/// the scene's first camera, which the solution carries in its field data, circling the scene
/// (the patches' bounds: CameraPath.h's OrbitPivot).
std::vector<sphcover::Camera> WalkCameras(const Options& options, const SavedSolution* saved)
{
  if (!options.PathFile.empty())
  {
    return sphcover::LoadCameraPath(options.PathFile);
  }
  const sphcover::Camera start = SceneCamera(saved->Illumination, "", options.SolutionFile);
  double bounds[6];
  vtkDataSet::SafeDownCast(saved->Patches)->GetBounds(bounds);
  const glm::dvec3 lower(bounds[0], bounds[2], bounds[4]);
  const glm::dvec3 upper(bounds[1], bounds[3], bounds[5]);
  return sphcover::OrbitPath(start, options.Orbit, sphcover::OrbitPivot(start, lower, upper));
}

/// --size: every camera at width x height (nothing when 0).
void ResizeCameras(int width, int height, std::vector<sphcover::Camera>& cameras)
{
  for (sphcover::Camera& camera : cameras)
  {
    camera.Width = width > 0 ? width : camera.Width;
    camera.Height = height > 0 ? height : camera.Height;
  }
}

/// Refuses a camera the renderer cannot render within the budgets before any frame is written,
/// naming the camera's place in the path.
void CheckWalkBudgets(const Options& options,
  const std::vector<sphcover::Camera>& cameras,
  const sphcover::RenderSettings& settings)
{
  for (std::size_t k = 0; k < cameras.size(); ++k)
  {
    const std::string problem = sphcover::CheckCamera(cameras[k], settings);
    if (!problem.empty())
    {
      const std::string where = options.PathFile.empty()
        ? "--orbit camera " + std::to_string(k)
        : options.PathFile + ": /cameras/" + std::to_string(k);
      throw std::runtime_error(
        where + ": " + problem + " (--memory-limit and --max-samples raise the limits)");
    }
  }
}

std::string Milliseconds(double seconds)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(1) << 1000.0 * seconds;
  return text.str();
}
}

int RunWalk(const Options& options)
{
  // Under mpiexec a solution in as many pieces as ranks is rendered by the ranks together
  // (vtkRankRenderer), each holding its own share of the cover; any other solution by rank 0.
  vtkMultiProcessController* controller =
    options.Ranks > 1 ? vtkMultiProcessController::GetGlobalController() : nullptr;
  // Everything that can be checked is checked before the solution is read and before any
  // frame is written: the options, the frames' folder, the path file (rank 0's checks, which
  // the ranks that read pieces agree on).
  std::vector<sphcover::Camera> cameras;
  int width = 0;
  int height = 0;
  const sphcover::RenderSettings settings = RenderBudget(options);
  std::string problem;
  if (options.Rank == 0)
  {
    try
    {
      if (options.PathFile.empty() == (options.Orbit == 0))
      {
        throw std::runtime_error("give the cameras: either --path PATH.json or --orbit N");
      }
      if (!(options.ExposureFactor > 0.0 && std::isfinite(options.ExposureFactor)))
      {
        std::ostringstream text;
        text << "--exposure " << options.ExposureFactor << ": must be a finite number > 0";
        throw std::runtime_error(text.str());
      }
      CheckFrameFolder(options.Output);
      CheckOutputPath("--report", options.Report, { ".json" }, "report");
      if (!options.Size.empty())
      {
        ParseSize(options.Size, width, height);
      }
      if (!options.PathFile.empty())
      {
        cameras = WalkCameras(options, nullptr);
      }
      ResizeCameras(width, height, cameras);
      CheckWalkBudgets(options, cameras, settings);
    }
    catch (const std::exception& e)
    {
      problem = e.what();
    }
  }
  // The solution, read once.
  SavedSolution saved;
  saved.Option.clear();
  const bool pieces = controller && saved.ReadPiece(options, controller, problem);
  if (!pieces)
  {
    if (options.Rank > 0)
    {
      return 0; // rank 0 walks alone
    }
    if (!problem.empty())
    {
      throw std::runtime_error(problem);
    }
    ErrorCollector errors;
    saved.Read(options, errors);
  }
  // Its renderer, built once: the ray caster over the patches' tessellation and the
  // interpolation of the characteristic points (paper §5.3); of pieces, each rank's own.
  const auto buildStart = std::chrono::steady_clock::now();
  std::unique_ptr<sphcover::RadianceRenderer> renderer;
  try
  {
    if (!vtkDataSet::SafeDownCast(saved.Patches))
    {
      throw std::runtime_error("'" + options.SolutionFile +
        "': its first block is not a dataset of patches (not a solution of sphcover solve -o)");
    }
    if (options.Rank == 0 && options.PathFile.empty())
    {
      cameras = WalkCameras(options, &saved);
      ResizeCameras(width, height, cameras);
      CheckWalkBudgets(options, cameras, settings);
    }
    renderer = vtkSolutionRenderer::New(
      saved.Illumination, vtkDataSet::SafeDownCast(saved.Patches), problem, pieces);
    if (!renderer)
    {
      throw std::runtime_error("'" + options.SolutionFile + "': cannot render: " + problem);
    }
    problem.clear();
  }
  catch (const std::exception& e)
  {
    problem = e.what();
  }
  if (pieces)
  {
    problem = vtkCoverDistribution::Agree(controller, problem);
  }
  if (!problem.empty())
  {
    throw std::runtime_error(problem);
  }
  const double buildSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - buildStart).count();
  std::unique_ptr<vtkRankRenderer> ranks =
    pieces ? std::make_unique<vtkRankRenderer>(controller, *renderer) : nullptr;
  if (options.Rank > 0)
  {
    ranks->Serve(vtkSMPParallelFor::Make());
    return 0; // rank 0 writes the frames
  }
  std::error_code error;
  fs::create_directories(options.Output, error);
  if (error)
  {
    throw std::runtime_error("cannot create '" + options.Output + "': " + error.message());
  }

  // The frames: each rendered and written whole (OutputFiles.h) before the next; an interrupt
  // leaves the frames before it and no partial one.
  std::vector<double> renderSeconds;
  std::vector<std::string> written;
  nlohmann::json frames = nlohmann::json::array();
  {
    ProgressBar bar("walk", options.Quiet);
    bar.Update(0.0);
    for (std::size_t k = 0; k < cameras.size(); ++k)
    {
      sphcover::RenderedImage image;
      const auto start = std::chrono::steady_clock::now();
      if (ranks)
      {
        ranks->Render(cameras[k], settings, image, vtkSMPParallelFor::Make(), nullptr);
      }
      else
      {
        renderer->Render(cameras[k], settings, image, vtkSMPParallelFor::Make());
      }
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      renderSeconds.push_back(seconds);
      vtkNew<vtkImageData> frame;
      vtkSolutionRenderer::ToImageData(image, options.ExposureFactor, frame);
      const std::string stem = (fs::path(options.Output) / FrameStem(k, cameras.size())).string();
      WritePngAtomically(frame, stem + ".png");
      written.push_back(stem + ".png");
      if (options.Exr)
      {
        WriteExrAtomically(frame, stem + ".exr");
        written.push_back(stem + ".exr");
      }
      frames.push_back({ { "file", stem + ".png" },
        { "width", image.Width },
        { "height", image.Height },
        { "render_ms", 1000.0 * seconds } });
      bar.Update(static_cast<double>(k + 1) / cameras.size());
    }
  }

  double total = 0.0;
  for (const double seconds : renderSeconds)
  {
    total += seconds;
  }
  const double mean = total / renderSeconds.size();
  if (!options.Report.empty())
  {
    nlohmann::json report;
    report["solution"] = options.SolutionFile;
    report["samples_per_pixel"] = options.SamplesPerPixel;
    report["read_s"] = saved.ReadSeconds;
    report["renderer_build_s"] = buildSeconds;
    report["render_ms_mean"] = 1000.0 * mean;
    report["frames"] = frames;
    WriteTextAtomically(report.dump(2) + "\n", options.Report);
  }
  for (std::size_t k = 0; k < renderSeconds.size(); ++k)
  {
    std::cout << "frame " << k << ": " << Milliseconds(renderSeconds[k]) << " ms\n";
  }
  std::cout << "frames: " << cameras.size() << ", " << options.SamplesPerPixel
            << " samples per pixel\n"
            << "seconds: read " << saved.ReadSeconds << ", renderer " << buildSeconds << "\n"
            << "ms per frame: " << Milliseconds(mean) << " (render only, mean)\n";
  std::cout << "written: " << written.size() << " files in " << options.Output << "\n";
  return 0;
}
}
