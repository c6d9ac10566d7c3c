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

#include "vtkRadianceImageFilter.h"

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
/// "WxH" as two positive integers.
void ParseSize(const std::string& text, int& width, int& height)
{
  const size_t x = text.find('x');
  size_t used1 = 0;
  size_t used2 = 0;
  try
  {
    if (x == std::string::npos)
    {
      throw std::invalid_argument(text);
    }
    width = std::stoi(text.substr(0, x), &used1);
    height = std::stoi(text.substr(x + 1), &used2);
  }
  catch (const std::exception&)
  {
    used1 = 0;
  }
  if (used1 == 0 || used1 != x || used2 != text.size() - x - 1 || width < 1 || height < 1)
  {
    throw std::runtime_error("--size '" + text + "': expected WIDTHxHEIGHT, e.g. 640x480");
  }
}
}

int RunRender(const Options& options)
{
  // The outputs, checked before any work: -o is the HDR image (.exr, Radiance and Depth) or a
  // tone-mapped PNG; --png adds a tone-mapped PNG.
  CheckOutputPath("-o", options.Output, { ".exr", ".png" }, "image");
  CheckOutputPath("--png", options.Png, { ".png" }, "image");
  CheckOutputPath("--report", options.Report, { ".json" }, "report");
  std::string exr;
  std::vector<std::string> pngs;
  if (!options.Output.empty())
  {
    if (ExtensionOf(options.Output) == ".exr")
    {
      exr = options.Output;
    }
    else
    {
      pngs.push_back(options.Output);
    }
  }
  if (!options.Png.empty())
  {
    pngs.push_back(options.Png);
  }
  if (exr.empty() && pngs.empty())
  {
    throw std::runtime_error("no output: give -o out.exr, -o out.png or --png out.png");
  }
  std::vector<std::string> outputs = pngs;
  if (!exr.empty())
  {
    outputs.push_back(exr);
  }
  // A zero, negative or non-finite exposure maps every radiance to black (or NaN).
  if (!(options.Exposure > 0.0 && std::isfinite(options.Exposure)))
  {
    std::ostringstream text;
    text << "--exposure " << options.Exposure << ": must be a finite number > 0";
    throw std::runtime_error(text.str());
  }

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

  SavedSolution saved;
  ErrorCollector errors;
  nlohmann::json timings;
  vtkPolyData* illumination = nullptr;
  vtkAlgorithmOutput* illuminationPort = nullptr;
  vtkAlgorithmOutput* patchesPort = nullptr;
  vtkNew<vtkTrivialProducer> illuminationProducer;
  vtkNew<vtkTrivialProducer> patchesProducer;
  if (solving)
  {
    solution.Solve(options);
    illuminationPort = solution.Propagation->GetOutputPort(0);
    patchesPort = solution.Subdivision->GetOutputPort(0);
    illumination = solution.Propagation->GetOutput();
    timings = solution.Timings();
  }
  else
  {
    saved.Read(options, errors);
    timings["read"] = saved.ReadSeconds;
    saved.CheckFingerprint(options, solution.Reader->GetOutput());
    illumination = saved.Illumination;
    patchesProducer->SetOutput(saved.Patches);
    illuminationProducer->SetOutput(illumination);
    illuminationPort = illuminationProducer->GetOutputPort();
    patchesPort = patchesProducer->GetOutputPort();
  }

  vtkNew<vtkRadianceImageFilter> render;
  render->SetInputConnection(0, illuminationPort);
  render->SetPatchesConnection(patchesPort);
  render->SetPosition(camera.Position.x, camera.Position.y, camera.Position.z);
  render->SetFocalPoint(camera.FocalPoint.x, camera.FocalPoint.y, camera.FocalPoint.z);
  render->SetViewUp(camera.ViewUp.x, camera.ViewUp.y, camera.ViewUp.z);
  render->SetViewAngle(camera.ViewAngle);
  render->SetWidth(width);
  render->SetHeight(height);
  render->SetSamplesPerPixel(options.SamplesPerPixel);
  render->SetExposure(options.Exposure);
  render->SetMemoryLimit(options.MemoryLimit);
  render->SetMaximumSamples(options.MaxSamples);
  double renderSeconds = 0.0;
  {
    ProgressBar bar(render, "render", options.Quiet);
    Run(render, errors);
    renderSeconds = bar.Seconds();
  }
  timings["render"] = renderSeconds;

  // The report is computed before any file is written: a solution it cannot read fails the
  // command without leaving an image behind. A saved solution's figures are computed again
  // from its arrays (they are what the image shows).
  nlohmann::json report;
  if (!options.Report.empty())
  {
    if (solving)
    {
      report = SolutionReport(solution);
    }
    else
    {
      const std::string problem = vtkLightPropagationFilter::AddSolutionFigures(illumination);
      if (!problem.empty())
      {
        throw std::runtime_error(problem);
      }
      ReportCounts counts;
      auto* patches = vtkDataSet::SafeDownCast(saved.Patches);
      counts.Patches = patches ? patches->GetNumberOfCells() : -1;
      report = Report(illumination, counts);
    }
    report["timings_s"] = timings;
    report["image"] = { { "camera", camera.Name },
      { "width", width },
      { "height", height },
      { "samples_per_pixel", options.SamplesPerPixel } };
  }
  if (!exr.empty())
  {
    WriteExrAtomically(render->GetOutput(), exr);
  }
  for (const std::string& png : pngs)
  {
    WritePngAtomically(render->GetOutput(), png);
  }
  if (!options.Report.empty())
  {
    WriteTextAtomically(report.dump(2) + "\n", options.Report);
  }
  std::cout << "image: " << width << "x" << height << " from camera '" << camera.Name << "', "
            << options.SamplesPerPixel << " samples per pixel\n"
            << "seconds: render " << renderSeconds << "\n";
  for (const std::string& path : outputs)
  {
    std::cout << "written: " << path << "\n";
  }
  return 0;
}
}
