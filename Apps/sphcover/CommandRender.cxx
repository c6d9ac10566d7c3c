// SPDX-License-Identifier: BSD-3-Clause
// sphcover render SCENE: the whole pipeline (or a saved solution, --solution) and the image of
// paper §5.3 through one of the scene's cameras, as HDR OpenEXR and/or tone-mapped PNG.
#include "Budgets.h"
#include "Commands.h"
#include "Options.h"
#include "OutputFiles.h"
#include "Pipeline.h"
#include "ProgressBar.h"
#include "Report.h"
#include "SavedSolution.h"
#include "SceneCamera.h"

#include "vtkCoverDistribution.h"
#include "vtkRadianceImageFilter.h"
#include "vtkRankRenderer.h"
#include "vtkSMPParallelFor.h"
#include "vtkSolutionRenderer.h"

#include <vtkImageData.h>
#include <vtkMultiProcessController.h>
#include <vtkPolyData.h>
#include <vtkTrivialProducer.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace sphcover_cli
{
namespace
{
/// The image files -o and --png name: -o is the HDR image (.exr, Radiance and Depth as Z) or a
/// tone-mapped PNG; --png adds a tone-mapped PNG.
struct RenderOutputs
{
  std::string Exr;
  std::vector<std::string> Pngs;
  /// The PNGs, then the EXR: the order the command lists them as written.
  std::vector<std::string> Written;
};

/// The outputs, checked before any work (their paths and the exposure the PNGs are mapped with).
RenderOutputs ChooseOutputs(const Options& options)
{
  CheckOutputPath("-o", options.Output, { ".exr", ".png" }, "image");
  CheckOutputPath("--png", options.Png, { ".png" }, "image");
  CheckOutputPath("--report", options.Report, { ".json" }, "report");
  RenderOutputs outputs;
  if (!options.Output.empty())
  {
    if (ExtensionOf(options.Output) == ".exr")
    {
      outputs.Exr = options.Output;
    }
    else
    {
      outputs.Pngs.push_back(options.Output);
    }
  }
  if (!options.Png.empty())
  {
    outputs.Pngs.push_back(options.Png);
  }
  if (outputs.Exr.empty() && outputs.Pngs.empty())
  {
    throw std::runtime_error("no output: give -o out.exr, -o out.png or --png out.png");
  }
  outputs.Written = outputs.Pngs;
  if (!outputs.Exr.empty())
  {
    outputs.Written.push_back(outputs.Exr);
  }
  // A zero, negative or non-finite exposure maps every radiance to black (or NaN).
  if (!(options.ExposureFactor > 0.0 && std::isfinite(options.ExposureFactor)))
  {
    std::ostringstream text;
    text << "--exposure " << options.ExposureFactor << ": must be a finite number > 0";
    throw std::runtime_error(text.str());
  }
  return outputs;
}

/// What the renderer reads: the solved pipeline's outputs, or a saved solution's blocks
/// through trivial producers.
struct RenderSource
{
  nlohmann::json Timings;
  /// The same stages' processor seconds (the report's `timings_cpu_s`).
  nlohmann::json CpuTimings;
  vtkPolyData* Illumination = nullptr;
  vtkAlgorithmOutput* IlluminationPort = nullptr;
  vtkAlgorithmOutput* PatchesPort = nullptr;
  vtkNew<vtkTrivialProducer> IlluminationProducer;
  vtkNew<vtkTrivialProducer> PatchesProducer;
};

/// Solves the scene (no --solution) or reads --solution and checks that it was computed from
/// this scene; `source` then names the illumination and patches the renderer reads.
void ConnectSolution(const Options& options,
  bool solving,
  Solution& solution,
  SavedSolution& saved,
  ErrorCollector& errors,
  RenderSource& source)
{
  if (solving)
  {
    solution.Solve(options);
    source.IlluminationPort = solution.Propagation->GetOutputPort(0);
    source.PatchesPort = solution.Subdivision->GetOutputPort(0);
    source.Illumination = solution.Propagation->GetOutput();
    source.Timings = solution.Timings();
    source.CpuTimings = solution.CpuTimings();
  }
  else
  {
    const double cpuStart = ProcessorSeconds();
    saved.Read(options, errors);
    source.CpuTimings["read"] = ProcessorSeconds() - cpuStart;
    source.Timings["read"] = saved.ReadSeconds;
    saved.CheckFingerprint(options, solution.Reader->GetOutput());
    source.Illumination = saved.Illumination;
    source.PatchesProducer->SetOutput(saved.Patches);
    source.IlluminationProducer->SetOutput(source.Illumination);
    source.IlluminationPort = source.IlluminationProducer->GetOutputPort();
    source.PatchesPort = source.PatchesProducer->GetOutputPort();
  }
}

/// The image filter of paper §5.3 on `source`, through `camera` at width x height.
void SetUpRender(vtkRadianceImageFilter* render,
  const RenderSource& source,
  const sphcover::Camera& camera,
  int width,
  int height,
  const Options& options)
{
  render->SetInputConnection(0, source.IlluminationPort);
  render->SetPatchesConnection(source.PatchesPort);
  render->SetPosition(camera.Position.x, camera.Position.y, camera.Position.z);
  render->SetFocalPoint(camera.FocalPoint.x, camera.FocalPoint.y, camera.FocalPoint.z);
  render->SetViewUp(camera.ViewUp.x, camera.ViewUp.y, camera.ViewUp.z);
  render->SetViewAngle(camera.ViewAngle);
  render->SetWidth(width);
  render->SetHeight(height);
  render->SetSamplesPerPixel(options.SamplesPerPixel);
  render->SetExposureFactor(options.ExposureFactor);
  render->SetMemoryLimit(options.MemoryLimit);
  render->SetMaximumSamples(options.MaxSamples);
}

/// The report's view of the image.
nlohmann::json ImageReport(const Options& options, const sphcover::Camera& camera)
{
  return { { "camera", camera.Name },
    { "width", camera.Width },
    { "height", camera.Height },
    { "samples_per_pixel", options.SamplesPerPixel } };
}

/// The --report document: the solution's figures (a saved solution's computed again from its
/// arrays: they are what the image shows), the timings and the image's camera and size.
nlohmann::json RenderReport(const Options& options,
  bool solving,
  Solution& solution,
  const SavedSolution& saved,
  const RenderSource& source,
  const sphcover::Camera& camera,
  int width,
  int height)
{
  nlohmann::json report;
  if (solving)
  {
    report = SolutionReport(solution);
  }
  else
  {
    const std::string problem = vtkLightPropagationFilter::AddSolutionFigures(source.Illumination);
    if (!problem.empty())
    {
      throw std::runtime_error(problem);
    }
    ReportCounts counts;
    auto* patches = vtkDataSet::SafeDownCast(saved.Patches);
    counts.Patches = patches ? patches->GetNumberOfCells() : -1;
    report = Report(source.Illumination, counts);
  }
  report["timings_s"] = source.Timings;
  report["timings_cpu_s"] = source.CpuTimings;
  sphcover::Camera sized = camera;
  sized.Width = width;
  sized.Height = height;
  report["image"] = ImageReport(options, sized);
  return report;
}

/// Writes the image files and the report, and prints what was written.
void WriteRender(const Options& options,
  const RenderOutputs& outputs,
  vtkImageData* image,
  const nlohmann::json& report,
  const sphcover::Camera& camera,
  double renderSeconds)
{
  if (!outputs.Exr.empty())
  {
    WriteExrAtomically(image, outputs.Exr);
  }
  for (const std::string& png : outputs.Pngs)
  {
    WritePngAtomically(image, png);
  }
  if (!options.Report.empty())
  {
    WriteTextAtomically(report.dump(2) + "\n", options.Report);
  }
  std::cout << "image: " << image->GetDimensions()[0] << "x" << image->GetDimensions()[1]
            << " from camera '" << camera.Name << "', " << options.SamplesPerPixel
            << " samples per pixel\n"
            << "seconds: render " << renderSeconds << "\n";
  for (const std::string& path : outputs.Written)
  {
    std::cout << "written: " << path << "\n";
  }
}

/// What the ranks' render gives rank 0.
struct RankImage
{
  vtkNew<vtkImageData> Image;
  double Seconds = 0.0;
  double CpuSeconds = 0.0;
};

/**
 * A solution kept in pieces rendered by the ranks that hold them (vtkRankRenderer): each builds
 * its renderer from its piece (`illumination`) and the patches, rank 0 renders the view with
 * every rank's directional values. `problem` is what a rank found before ("" if nothing),
 * agreed with the renderers' problems. Collective; true on rank 0 with the image in `result`,
 * false on the others once rank 0 is finished.
 */
bool RenderOnRanks(const Options& options,
  vtkPolyData* illumination,
  vtkDataSet* patches,
  const std::string& named,
  std::string problem,
  const sphcover::Camera& camera,
  const sphcover::RenderSettings& settings,
  RankImage& result)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  std::unique_ptr<sphcover::RadianceRenderer> renderer;
  if (problem.empty())
  {
    try
    {
      renderer = vtkSolutionRenderer::New(illumination, patches, problem, true);
      if (!renderer)
      {
        throw std::runtime_error(named + "cannot render: " + problem);
      }
      problem.clear();
    }
    catch (const std::exception& e)
    {
      problem = e.what();
    }
  }
  problem = vtkCoverDistribution::Agree(controller, problem);
  if (!problem.empty())
  {
    throw std::runtime_error(problem);
  }
  vtkRankRenderer ranks(controller, *renderer);
  if (options.Rank > 0)
  {
    ranks.Serve(vtkSMPParallelFor::Make());
    return false;
  }
  sphcover::RenderedImage rendered;
  const double cpuStart = ProcessorSeconds();
  {
    ProgressBar bar("render", options.Quiet);
    bar.Update(0.0);
    ranks.Render(camera,
      settings,
      rendered,
      vtkSMPParallelFor::Make(),
      [&bar](double fraction)
      {
        bar.Update(fraction);
        return true;
      });
    result.Seconds = bar.Seconds();
  }
  result.CpuSeconds = ProcessorSeconds() - cpuStart;
  ranks.Finish();
  vtkSolutionRenderer::ToImageData(rendered, options.ExposureFactor, result.Image);
  return true;
}
}

int RunRender(const Options& options)
{
  const RenderOutputs outputs = ChooseOutputs(options);

  // The scene (read once, its cameras and fingerprint in the reader's field data), then the
  // camera: --camera or the scene's first, --size or the camera's size.
  Solution solution;
  const bool solving = options.SolutionFile.empty();
  solution.Read(options, solving);
  const sphcover::Camera camera =
    SceneCamera(solution.Reader->GetOutput(), options.Camera, options.Scene);
  int width = camera.Width;
  int height = camera.Height;
  if (!options.Size.empty())
  {
    ParseSize(options.Size, width, height);
  }
  const sphcover::RenderSettings renderSettings = RenderBudget(options);
  CheckRenderBudget(camera, width, height, renderSettings);

  // Under mpiexec the ranks solve together and keep the solution in pieces, or read a
  // solution kept in as many pieces as ranks, and render it together, no rank holding the
  // whole cover (RenderOnRanks); rank 0 alone renders any other saved solution and writes.
  sphcover::Camera sized = camera;
  sized.Width = width;
  sized.Height = height;
  RankImage ranked;
  if (solving && options.Ranks > 1)
  {
    solution.Solve(options, false);
    if (!RenderOnRanks(options,
          solution.Propagation->GetOutput(),
          solution.Subdivision->GetOutput(),
          "",
          "",
          sized,
          renderSettings,
          ranked))
    {
      return 0;
    }
    nlohmann::json report;
    if (!options.Report.empty())
    {
      report = SolutionReport(solution);
      report["timings_s"] = solution.Timings();
      report["timings_s"]["render"] = ranked.Seconds;
      report["timings_cpu_s"] = solution.CpuTimings();
      report["timings_cpu_s"]["render"] = ranked.CpuSeconds;
      report["image"] = ImageReport(options, sized);
    }
    WriteRender(options, outputs, ranked.Image, report, camera, ranked.Seconds);
    return 0;
  }
  if (!solving && options.Ranks > 1)
  {
    SavedSolution pieces;
    if (pieces.ReadPiece(options, vtkMultiProcessController::GetGlobalController(), ""))
    {
      std::string problem;
      try
      {
        pieces.CheckFingerprint(options, solution.Reader->GetOutput());
      }
      catch (const std::exception& e)
      {
        problem = e.what();
      }
      if (!RenderOnRanks(options,
            pieces.Illumination,
            vtkDataSet::SafeDownCast(pieces.Patches),
            "--solution '" + options.SolutionFile + "': ",
            problem,
            sized,
            renderSettings,
            ranked))
      {
        return 0;
      }
      // The figures the solve stored with the pieces (the whole cover is nowhere).
      nlohmann::json report;
      if (!options.Report.empty())
      {
        ReportCounts counts;
        counts.Patches = vtkDataSet::SafeDownCast(pieces.Patches)->GetNumberOfCells();
        report = Report(pieces.Illumination, counts);
        report["timings_s"] = { { "read", pieces.ReadSeconds }, { "render", ranked.Seconds } };
        report["timings_cpu_s"] = { { "render", ranked.CpuSeconds } };
        report["ranks"] = options.Ranks;
        report["image"] = ImageReport(options, sized);
      }
      WriteRender(options, outputs, ranked.Image, report, camera, ranked.Seconds);
      return 0;
    }
  }
  if (options.Rank > 0 && !solving)
  {
    return 0;
  }
  SavedSolution saved;
  ErrorCollector errors;
  RenderSource source;
  ConnectSolution(options, solving, solution, saved, errors, source);
  if (options.Rank > 0)
  {
    return 0;
  }

  vtkNew<vtkRadianceImageFilter> render;
  SetUpRender(render, source, camera, width, height, options);
  double renderSeconds = 0.0;
  {
    ProgressBar bar(render, "render", options.Quiet);
    const double cpuStart = ProcessorSeconds();
    Run(render, errors);
    source.CpuTimings["render"] = ProcessorSeconds() - cpuStart;
    renderSeconds = bar.Seconds();
  }
  source.Timings["render"] = renderSeconds;

  // The report is computed before any file is written: a solution it cannot read fails the
  // command without leaving an image behind.
  nlohmann::json report;
  if (!options.Report.empty())
  {
    report = RenderReport(options, solving, solution, saved, source, camera, width, height);
    AddPaneLimit(report, nullptr, render->GetOutput()->GetFieldData());
  }
  WriteRender(options, outputs, render->GetOutput(), report, camera, renderSeconds);
  return 0;
}
}
