// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file main.cxx
 * @brief `sphcover`: the command-line program (SPEC §5).
 *
 *   sphcover info SCENE
 *   sphcover subdivide SCENE -o patches.vtm [--range-method bernstein|natural] [--set k=v]...
 *   sphcover solve SCENE [-o solution.vtm] [--report report.json] [--fill projection|raycasting]
 *   sphcover render SCENE [-o out.exr|out.png] [--png out.png] [--camera NAME] [--size WxH] [--spp
 * N]
 *                   [--exposure E] [--solution solution.vtm] [--report report.json] [--set k=v]
 *
 * Every error is one line on stderr and a non-zero exit status; no output file is left
 * half-written, also when interrupted (OutputFiles.h).
 */
#include "ErrorCollector.h"
#include "OutputFiles.h"
#include "ProgressBar.h"
#include "SceneSummary.h"

#include "vtkIntervalSubdivisionFilter.h"
#include "vtkLightPropagationFilter.h"
#include "vtkPatchSceneReader.h"
#include "vtkRadianceImageFilter.h"
#include "vtkSceneFileLoader.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSphericalCoverArrays.h"
#include "vtkSphericalCoverFilter.h"

#include "cover/SphericalCover.h"
#include "render/RadianceRenderer.h"
#include "scene/InputError.h"
#include "scene/Scene.h"
#include "scene/SettingsOverride.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkLogger.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkStringArray.h>
#include <vtkStringOutputWindow.h>
#include <vtkTrivialProducer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLMultiBlockDataReader.h>
#include <vtkXMLMultiBlockDataWriter.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace
{
struct Options
{
  std::string Scene;
  std::string Output;
  std::string RangeMethod = "bernstein";
  std::string Report;
  std::string Fill = "projection";
  std::vector<std::string> Settings;
  std::string Png;
  std::string Camera;
  std::string Size;
  std::string SolutionFile;
  int SamplesPerPixel = 4;
  double Exposure = 1.0;
  int Threads = 0;
  bool Quiet = false;
  /// The budgets (see the options' help): what a stage may take before it refuses.
  double MemoryLimit = 8192.0;
  int MaxPatches = 1000000;
  double MaxPairTests = 1.0e9;
  double MaxSamples = 1073741824.0;
};

/// The name of the illumination's field data array that holds the scene's fingerprint
/// (sphcover::Fingerprint) in a solution written by `solve -o`.
constexpr const char* SceneFingerprintArray = "SceneFingerprint";

/// Updates an algorithm; on failure throws its first error as one line.
void Run(vtkAlgorithm* algorithm, ErrorCollector& errors)
{
  errors.Watch(algorithm);
  if (algorithm->GetExecutive()->Update() != 1)
  {
    throw std::runtime_error(errors.First());
  }
}

/// The scene's settings block as the reader passed it on, with the --set overrides applied.
sphcover::SceneSettings SettingsOf(vtkDataObject* surfaces, const std::vector<std::string>& sets)
{
  sphcover::SceneSettings settings;
  vtkDataArray* values =
    surfaces->GetFieldData()->GetArray(vtkSphericalCoverArrayNames::SceneSettings);
  if (values && values->GetNumberOfComponents() == 4)
  {
    settings.ThetaBins = static_cast<int>(values->GetComponent(0, 0));
    settings.PhiBins = static_cast<int>(values->GetComponent(0, 1));
    settings.MaxLevel = static_cast<int>(values->GetComponent(0, 2));
    settings.Tolerance = values->GetComponent(0, 3);
  }
  for (const std::string& assignment : sets)
  {
    settings = sphcover::OverrideSetting(settings, assignment);
  }
  return settings;
}

/// Refuses, before the subdivision, a cover grid whose R-buffers alone (one per thread) exceed
/// --memory-limit: known from the settings, so nothing is subdivided or allocated in vain.
void CheckCoverGrid(const sphcover::SceneSettings& settings, const Options& options)
{
  sphcover::SphericalCoverOptions cover;
  cover.ThetaBins = settings.ThetaBins;
  cover.PhiBins = settings.PhiBins;
  const std::size_t threads =
    static_cast<std::size_t>(std::max(1, vtkSMPTools::GetEstimatedNumberOfThreads()));
  const std::string problem = sphcover::SphericalCover::MemoryProblem(
    {}, cover, threads, static_cast<std::size_t>(options.MemoryLimit * 1024.0 * 1024.0));
  if (!problem.empty())
  {
    throw std::runtime_error(options.Scene + ": settings theta_bins " +
      std::to_string(settings.ThetaBins) + ", phi_bins " + std::to_string(settings.PhiBins) + ": " +
      problem + " (--memory-limit)");
  }
}

/// The stages up to the spherical cover, run with progress bars; errors throw one line.
struct Solution
{
  vtkNew<vtkPatchSceneReader> Reader;
  vtkNew<vtkIntervalSubdivisionFilter> Subdivision;
  vtkNew<vtkSphericalCoverFilter> Cover;
  vtkNew<vtkLightPropagationFilter> Propagation;
  double ReadSeconds = 0.0;
  double SubdivideSeconds = 0.0;
  double CoverSeconds = 0.0;
  double PropagateSeconds = 0.0;

  void Run(const Options& options)
  {
    ErrorCollector errors;
    this->Reader->SetFileName(options.Scene.c_str());
    {
      ProgressBar bar(this->Reader, "read", options.Quiet);
      ::Run(this->Reader, errors);
      this->ReadSeconds = bar.Seconds();
    }
    const sphcover::SceneSettings settings =
      SettingsOf(this->Reader->GetOutput(), options.Settings);
    CheckCoverGrid(settings, options);
    this->Subdivision->SetInputConnection(this->Reader->GetOutputPort());
    this->Subdivision->SetMaximumPatches(options.MaxPatches);
    this->Subdivision->SetMaximumPairTests(options.MaxPairTests);
    this->Subdivision->SetMemoryLimit(options.MemoryLimit);
    this->Cover->SetMemoryLimit(options.MemoryLimit);
    this->Propagation->SetMemoryLimit(options.MemoryLimit);
    this->Subdivision->SetThetaBins(settings.ThetaBins);
    this->Subdivision->SetPhiBins(settings.PhiBins);
    this->Subdivision->SetMaxLevel(settings.MaxLevel);
    this->Subdivision->SetTolerance(settings.Tolerance);
    if (options.RangeMethod == "natural")
    {
      this->Subdivision->SetRangeMethodToNaturalInterval();
    }
    {
      ProgressBar bar(this->Subdivision, "subdivide", options.Quiet);
      ::Run(this->Subdivision, errors);
      this->SubdivideSeconds = bar.Seconds();
    }
    this->Cover->SetInputConnection(this->Subdivision->GetOutputPort(0));
    this->Cover->SetThetaBins(settings.ThetaBins);
    this->Cover->SetPhiBins(settings.PhiBins);
    if (options.Fill == "raycasting")
    {
      this->Cover->SetFillMethodToRayCasting();
    }
    {
      ProgressBar bar(this->Cover, "cover", options.Quiet);
      ::Run(this->Cover, errors);
      this->CoverSeconds = bar.Seconds();
    }
    this->Propagation->SetInputConnection(this->Cover->GetOutputPort(0));
    {
      ProgressBar bar(this->Propagation, "propagate", options.Quiet);
      ::Run(this->Propagation, errors);
      this->PropagateSeconds = bar.Seconds();
    }
  }
};

/// Lower-case extension of a path, with its dot ("" if none).
std::string ExtensionOf(const std::string& path)
{
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return extension;
}

/**
 * Checks an output path before any work starts (a solve can take minutes; failing to write
 * afterwards wastes it): one of `extensions`, not a folder, in an existing folder this process
 * may write to. An empty path (the option not given) passes. Throws one line naming the option.
 */
void CheckOutputPath(const std::string& option,
  const std::string& path,
  const std::vector<std::string>& extensions,
  const std::string& kind)
{
  namespace fs = std::filesystem;
  if (path.empty())
  {
    return;
  }
  if (std::find(extensions.begin(), extensions.end(), ExtensionOf(path)) == extensions.end())
  {
    std::string expected;
    for (const std::string& extension : extensions)
    {
      expected += (expected.empty() ? "" : " or ") + extension;
    }
    throw std::runtime_error(
      option + " '" + path + "': unknown " + kind + " format (expected " + expected + ")");
  }
  std::error_code error;
  if (fs::is_directory(path, error))
  {
    throw std::runtime_error("cannot write '" + path + "': it is a folder");
  }
  const fs::path folder = fs::absolute(path).parent_path();
  if (!fs::is_directory(folder, error))
  {
    throw std::runtime_error("cannot write '" + path + "': no folder " + folder.string());
  }
  if (access(folder.c_str(), W_OK) != 0)
  {
    throw std::runtime_error(
      "cannot write '" + path + "': folder " + folder.string() + ": " + std::strerror(errno));
  }
}

/// The report of SPEC §5: per named surface its area and area-weighted mean irradiance and exitant
/// radiance, form factors between named surfaces (area-weighted over the source surface), the
/// energy balance, counts and timings.
/// What the report counts besides the illumination (-1: unknown, left out).
struct ReportCounts
{
  vtkIdType Surfaces = -1;
  vtkIdType Patches = -1;
  long long PairTests = -1;
  int Shots = -1;
};

nlohmann::json Report(vtkPolyData* points, const ReportCounts& counts)
{
  sphcover::SphericalCover cover;
  const std::string problem = vtkSphericalCoverArrays::Load(points, cover);
  if (!problem.empty())
  {
    throw std::runtime_error(problem);
  }
  auto* names = vtkStringArray::SafeDownCast(
    points->GetFieldData()->GetAbstractArray(vtkSphericalCoverArrayNames::SurfaceNames));
  vtkDataArray* nameId =
    points->GetPointData()->GetArray(vtkSphericalCoverArrayNames::SurfaceNameId);
  vtkDataArray* area = points->GetPointData()->GetArray(vtkSphericalCoverArrayNames::Area);
  if (!names || !nameId || !area)
  {
    throw std::runtime_error("the cover lacks the surface names or areas");
  }
  const int groups = static_cast<int>(names->GetNumberOfValues());
  std::vector<int> groupOfPatch(static_cast<size_t>(points->GetNumberOfPoints()));
  std::vector<double> groupArea(static_cast<size_t>(groups), 0.0);
  for (vtkIdType k = 0; k < points->GetNumberOfPoints(); ++k)
  {
    const double id = nameId->GetComponent(k, 0);
    if (!(id >= 0.0 && id < groups))
    {
      std::ostringstream text;
      text << "point " << k << " has SurfaceNameId " << id << ", not an index of the " << groups
           << " surface names";
      throw std::runtime_error(text.str());
    }
    groupOfPatch[static_cast<size_t>(k)] = static_cast<int>(id);
    groupArea[static_cast<size_t>(groupOfPatch[static_cast<size_t>(k)])] +=
      area->GetComponent(k, 0);
  }
  const std::vector<double> factors = cover.FormFactors(groupOfPatch, groups);
  vtkDataArray* irradiance =
    points->GetPointData()->GetArray(vtkSphericalCoverArrayNames::Irradiance);
  vtkDataArray* radiance = points->GetPointData()->GetArray(vtkSphericalCoverArrayNames::Radiosity);
  vtkDataArray* balance =
    points->GetFieldData()->GetArray(vtkSphericalCoverArrayNames::EnergyBalance);
  if (!irradiance || !radiance || !balance)
  {
    throw std::runtime_error("the illumination lacks Irradiance, Radiosity or EnergyBalance");
  }
  std::vector<glm::dvec3> meanIrradiance(static_cast<size_t>(groups), glm::dvec3(0.0));
  std::vector<glm::dvec3> meanRadiance(static_cast<size_t>(groups), glm::dvec3(0.0));
  for (vtkIdType k = 0; k < points->GetNumberOfPoints(); ++k)
  {
    const size_t g = static_cast<size_t>(groupOfPatch[static_cast<size_t>(k)]);
    const double weight = area->GetComponent(k, 0) / groupArea[g];
    for (int band = 0; band < 3; ++band)
    {
      meanIrradiance[g][band] += weight * irradiance->GetComponent(k, band);
      meanRadiance[g][band] += weight * radiance->GetComponent(k, band);
    }
  }
  auto triple = [](const glm::dvec3& v) { return nlohmann::json::array({ v.x, v.y, v.z }); };

  nlohmann::json report;
  report["surfaces"] = nlohmann::json::array();
  report["form_factors"]["names"] = nlohmann::json::array();
  report["form_factors"]["matrix"] = nlohmann::json::array();
  for (int a = 0; a < groups; ++a)
  {
    report["surfaces"].push_back({ { "name", names->GetValue(a) },
      { "area", groupArea[static_cast<size_t>(a)] },
      { "mean_irradiance", triple(meanIrradiance[static_cast<size_t>(a)]) },
      { "mean_exitant_radiance", triple(meanRadiance[static_cast<size_t>(a)]) } });
    report["form_factors"]["names"].push_back(names->GetValue(a));
    nlohmann::json row = nlohmann::json::array();
    for (int b = 0; b < groups; ++b)
    {
      row.push_back(factors[static_cast<size_t>(a * groups + b)]);
    }
    report["form_factors"]["matrix"].push_back(row);
  }
  glm::dvec3 emitted;
  glm::dvec3 absorbed;
  balance->GetTuple(0, &emitted[0]);
  balance->GetTuple(1, &absorbed[0]);
  double imbalance = 0.0;
  for (int band = 0; band < 3; ++band)
  {
    if (emitted[band] > 0.0)
    {
      imbalance = std::max(imbalance, std::fabs(emitted[band] - absorbed[band]) / emitted[band]);
    }
  }
  report["energy"] = { { "emitted_w", triple(emitted) },
    { "absorbed_w", triple(absorbed) },
    { "relative_imbalance", imbalance } };
  report["counts"] = { { "characteristic_points", points->GetNumberOfPoints() },
    { "strips", cover.StripCount() } };
  if (counts.Surfaces >= 0)
  {
    report["counts"]["surfaces"] = counts.Surfaces;
  }
  if (counts.Patches >= 0)
  {
    report["counts"]["patches"] = counts.Patches;
  }
  if (counts.PairTests >= 0)
  {
    report["counts"]["pair_tests"] = counts.PairTests;
  }
  if (counts.Shots >= 0)
  {
    report["counts"]["shots"] = counts.Shots;
  }
  return report;
}

/// The report of a solution computed in this run.
nlohmann::json Report(Solution& solution)
{
  ReportCounts counts;
  counts.Surfaces = solution.Reader->GetOutput()->GetNumberOfCells();
  counts.Patches = solution.Subdivision->GetOutput()->GetNumberOfCells();
  counts.PairTests = static_cast<long long>(solution.Subdivision->GetPairTests());
  counts.Shots = solution.Propagation->GetShots();
  nlohmann::json report = Report(solution.Propagation->GetOutput(), counts);
  report["timings_s"] = { { "read", solution.ReadSeconds },
    { "subdivide", solution.SubdivideSeconds },
    { "cover", solution.CoverSeconds },
    { "propagate", solution.PropagateSeconds } };
  return report;
}

int RunSolve(const Options& options)
{
  CheckOutputPath("-o", options.Output, { ".vtm" }, "solution");
  CheckOutputPath("--report", options.Report, { ".json" }, "report");
  Solution solution;
  solution.Run(options);
  if (!options.Report.empty())
  {
    sphcover_cli::WriteTextAtomically(Report(solution).dump(2) + "\n", options.Report);
  }
  if (!options.Output.empty())
  {
    vtkNew<vtkMultiBlockDataSet> blocks;
    blocks->SetNumberOfBlocks(2);
    blocks->SetBlock(0, solution.Subdivision->GetOutput());
    blocks->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "Patches");
    // The illumination carries the scene's fingerprint, so that `render --solution` can tell
    // a solution of another (or an edited) scene.
    vtkNew<vtkPolyData> illumination;
    illumination->ShallowCopy(solution.Propagation->GetOutput());
    vtkNew<vtkStringArray> fingerprint;
    fingerprint->SetName(SceneFingerprintArray);
    fingerprint->InsertNextValue(sphcover::Fingerprint(vtkSceneFileLoader::Load(options.Scene)));
    illumination->GetFieldData()->AddArray(fingerprint);
    blocks->SetBlock(1, illumination);
    blocks->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), "Illumination");
    vtkNew<vtkXMLMultiBlockDataWriter> writer;
    sphcover_cli::WriteXmlAtomically(writer, blocks, options.Output);
  }
  std::cout << "patches: " << solution.Subdivision->GetOutput()->GetNumberOfCells() << "\n"
            << "seconds: read " << solution.ReadSeconds << ", subdivide "
            << solution.SubdivideSeconds << ", cover " << solution.CoverSeconds << ", propagate "
            << solution.PropagateSeconds << " (" << solution.Propagation->GetShots() << " shots)\n";
  return 0;
}

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

/// The render's budgets from the options (--spp, --memory-limit, --max-samples).
sphcover::RenderSettings RenderBudget(const Options& options)
{
  sphcover::RenderSettings settings;
  settings.SamplesPerPixel = options.SamplesPerPixel;
  settings.MemoryLimitBytes = static_cast<std::size_t>(options.MemoryLimit * 1024.0 * 1024.0);
  settings.MaximumSamples = static_cast<std::size_t>(options.MaxSamples);
  return settings;
}

/// Refuses, before the solve, an image that exceeds the memory limit or the sample budget (it
/// would take hours): the same check the render filter makes, made before minutes of solving.
void CheckRenderBudget(sphcover::Camera camera,
  int width,
  int height,
  const sphcover::RenderSettings& settings)
{
  camera.Width = width;
  camera.Height = height;
  const std::string problem = sphcover::CheckCamera(camera, settings);
  if (!problem.empty())
  {
    throw std::runtime_error(
      "--size/--spp: " + problem + " (--memory-limit and --max-samples raise the limits)");
  }
}

/// A saved solution renders only with the scene it was solved from: its fingerprint (written
/// by `solve -o`) must be the scene file's (sphcover::Fingerprint).
void CheckFingerprint(const Options& options,
  vtkPolyData* illumination,
  const sphcover::Scene& scene)
{
  auto* stored = vtkStringArray::SafeDownCast(
    illumination->GetFieldData()->GetAbstractArray(SceneFingerprintArray));
  if (!stored || stored->GetNumberOfValues() != 1)
  {
    throw std::runtime_error("--solution '" + options.SolutionFile +
      "': has no scene fingerprint (not written by sphcover solve -o); solve the scene again");
  }
  const std::string expected = sphcover::Fingerprint(scene);
  if (stored->GetValue(0) != expected)
  {
    throw std::runtime_error("--solution '" + options.SolutionFile +
      "': solved from another scene than '" + options.Scene +
      "' (or from an edited one: fingerprint " + stored->GetValue(0) + ", the scene's " + expected +
      "); solve the scene again");
  }
}

/// sphcover render: the whole pipeline (or a saved solution) and the image of paper §5.3.
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

  // The camera: --camera or the scene's first, --size or the camera's size.
  const sphcover::Scene scene = vtkSceneFileLoader::Load(options.Scene);
  const sphcover::Camera* camera = nullptr;
  for (const sphcover::Camera& candidate : scene.Cameras)
  {
    if (options.Camera.empty() || candidate.Name == options.Camera)
    {
      camera = &candidate;
      break;
    }
  }
  if (!camera)
  {
    std::string names;
    for (const sphcover::Camera& candidate : scene.Cameras)
    {
      names += (names.empty() ? "'" : ", '") + candidate.Name + "'";
    }
    throw std::runtime_error(options.Scene + ": " +
      (options.Camera.empty() ? std::string("the scene has no camera")
                              : "no camera named '" + options.Camera + "'") +
      (names.empty() ? std::string() : " (cameras: " + names + ")"));
  }
  int width = camera->Width;
  int height = camera->Height;
  if (!options.Size.empty())
  {
    ParseSize(options.Size, width, height);
  }
  const sphcover::RenderSettings renderSettings = RenderBudget(options);
  CheckRenderBudget(*camera, width, height, renderSettings);

  Solution solution;
  vtkNew<vtkXMLMultiBlockDataReader> saved;
  nlohmann::json timings;
  vtkPolyData* illumination = nullptr;
  vtkDataObject* patches = nullptr;
  vtkAlgorithmOutput* illuminationPort = nullptr;
  vtkAlgorithmOutput* patchesPort = nullptr;
  vtkNew<vtkTrivialProducer> illuminationProducer;
  vtkNew<vtkTrivialProducer> patchesProducer;
  ErrorCollector errors;
  if (options.SolutionFile.empty())
  {
    solution.Run(options);
    illuminationPort = solution.Propagation->GetOutputPort(0);
    patchesPort = solution.Subdivision->GetOutputPort(0);
    illumination = solution.Propagation->GetOutput();
    timings = { { "read", solution.ReadSeconds },
      { "subdivide", solution.SubdivideSeconds },
      { "cover", solution.CoverSeconds },
      { "propagate", solution.PropagateSeconds } };
  }
  else
  {
    // A solution written by `sphcover solve -o`: block 0 the patches, block 1 the illumination.
    if (!std::filesystem::is_regular_file(options.SolutionFile))
    {
      throw std::runtime_error("--solution '" + options.SolutionFile + "': no such file");
    }
    saved->SetFileName(options.SolutionFile.c_str());
    {
      ProgressBar bar(saved, "read", options.Quiet);
      ::Run(saved, errors);
      timings["read"] = bar.Seconds();
    }
    auto* blocks = vtkMultiBlockDataSet::SafeDownCast(saved->GetOutputDataObject(0));
    patches = blocks && blocks->GetNumberOfBlocks() == 2 ? blocks->GetBlock(0) : nullptr;
    illumination = blocks && blocks->GetNumberOfBlocks() == 2
      ? vtkPolyData::SafeDownCast(blocks->GetBlock(1))
      : nullptr;
    if (!patches || !illumination)
    {
      throw std::runtime_error("--solution '" + options.SolutionFile +
        "': not a solution of sphcover solve -o (two blocks, the patches and the illumination)");
    }
    CheckFingerprint(options, illumination, scene);
    patchesProducer->SetOutput(patches);
    illuminationProducer->SetOutput(illumination);
    illuminationPort = illuminationProducer->GetOutputPort();
    patchesPort = patchesProducer->GetOutputPort();
  }

  vtkNew<vtkRadianceImageFilter> render;
  render->SetInputConnection(0, illuminationPort);
  render->SetPatchesConnection(patchesPort);
  render->SetPosition(camera->Position.x, camera->Position.y, camera->Position.z);
  render->SetFocalPoint(camera->FocalPoint.x, camera->FocalPoint.y, camera->FocalPoint.z);
  render->SetViewUp(camera->ViewUp.x, camera->ViewUp.y, camera->ViewUp.z);
  render->SetViewAngle(camera->ViewAngle);
  render->SetWidth(width);
  render->SetHeight(height);
  render->SetSamplesPerPixel(options.SamplesPerPixel);
  render->SetExposure(options.Exposure);
  render->SetMemoryLimit(options.MemoryLimit);
  render->SetMaximumSamples(options.MaxSamples);
  double renderSeconds = 0.0;
  {
    ProgressBar bar(render, "render", options.Quiet);
    ::Run(render, errors);
    renderSeconds = bar.Seconds();
  }
  timings["render"] = renderSeconds;

  // The report is computed before any file is written: a solution it cannot read fails the
  // command without leaving an image behind.
  nlohmann::json report;
  if (!options.Report.empty())
  {
    if (options.SolutionFile.empty())
    {
      report = Report(solution);
    }
    else
    {
      ReportCounts counts;
      counts.Patches = vtkDataSet::SafeDownCast(patches)
        ? vtkDataSet::SafeDownCast(patches)->GetNumberOfCells()
        : -1;
      report = Report(illumination, counts);
    }
    report["timings_s"] = timings;
    report["image"] = { { "camera", camera->Name },
      { "width", width },
      { "height", height },
      { "samples_per_pixel", options.SamplesPerPixel } };
  }
  if (!exr.empty())
  {
    sphcover_cli::WriteExrAtomically(render->GetOutput(), exr);
  }
  for (const std::string& png : pngs)
  {
    sphcover_cli::WritePngAtomically(render->GetOutput(), png);
  }
  if (!options.Report.empty())
  {
    sphcover_cli::WriteTextAtomically(report.dump(2) + "\n", options.Report);
  }
  std::cout << "image: " << width << "x" << height << " from camera '" << camera->Name << "', "
            << options.SamplesPerPixel << " samples per pixel\n"
            << "seconds: render " << renderSeconds << "\n";
  for (const std::string& path : outputs)
  {
    std::cout << "written: " << path << "\n";
  }
  return 0;
}

int RunInfo(const Options& options)
{
  const sphcover::Scene scene = vtkSceneFileLoader::Load(options.Scene);
  sphcover::PrintSceneSummary(scene, std::cout);
  return 0;
}

int RunSubdivide(const Options& options)
{
  CheckOutputPath("-o", options.Output, { ".vtm" }, "subdivision");
  ErrorCollector errors;
  vtkNew<vtkPatchSceneReader> reader;
  reader->SetFileName(options.Scene.c_str());
  {
    ProgressBar bar(reader, "read", options.Quiet);
    Run(reader, errors);
  }
  const sphcover::SceneSettings settings = SettingsOf(reader->GetOutput(), options.Settings);

  vtkNew<vtkIntervalSubdivisionFilter> subdivision;
  subdivision->SetInputConnection(reader->GetOutputPort());
  subdivision->SetThetaBins(settings.ThetaBins);
  subdivision->SetPhiBins(settings.PhiBins);
  subdivision->SetMaxLevel(settings.MaxLevel);
  subdivision->SetTolerance(settings.Tolerance);
  subdivision->SetMaximumPatches(options.MaxPatches);
  subdivision->SetMaximumPairTests(options.MaxPairTests);
  subdivision->SetMemoryLimit(options.MemoryLimit);
  if (options.RangeMethod == "natural")
  {
    subdivision->SetRangeMethodToNaturalInterval();
  }
  double seconds = 0.0;
  {
    ProgressBar bar(subdivision, "subdivide", options.Quiet);
    Run(subdivision, errors);
    seconds = bar.Seconds();
  }
  vtkUnstructuredGrid* patches = subdivision->GetOutput();
  auto* points = vtkPolyData::SafeDownCast(subdivision->GetOutputDataObject(1));

  vtkNew<vtkMultiBlockDataSet> blocks;
  blocks->SetNumberOfBlocks(2);
  blocks->SetBlock(0, patches);
  blocks->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "Patches");
  blocks->SetBlock(1, points);
  blocks->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), "CharacteristicPoints");
  vtkNew<vtkXMLMultiBlockDataWriter> writer;
  sphcover_cli::WriteXmlAtomically(writer, blocks, options.Output);

  std::cout << "patches: " << patches->GetNumberOfCells() << "\n"
            << "characteristic points: " << points->GetNumberOfPoints() << "\n"
            << "pair tests: " << subdivision->GetPairTests() << "\n"
            << "seconds: " << seconds << "\n"
            << "written: " << options.Output << "\n";
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
  Options options;
  app
    .add_option(
      "--threads", options.Threads, "Worker threads for the parallel stages (0: one per core)")
    ->check(CLI::Range(0, 4096));
  app.add_flag("--quiet,-q", options.Quiet, "No progress bars");
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
    "max_level, tolerance)");

  CLI::App* solve = app.add_subcommand("solve",
    "Run the method up to equilibrium (subdivision, spherical cover, light propagation) and "
    "write the solution and a JSON report (surfaces' mean irradiance and exitant radiance, form "
    "factors between named surfaces, energy balance, counts, timings)");
  solve->add_option("SCENE", options.Scene, "A .scene or .bpt file")->required();
  solve->add_option("-o,--output", options.Output, "Solution file (.vtm): patches and cover");
  solve->add_option("--report", options.Report, "Report file (.json)");
  solve->add_option("--fill", options.Fill, "R-buffer fill: projection (default) or raycasting")
    ->check(CLI::IsMember({ "projection", "raycasting" }));
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
    "Image file: .exr (HDR Radiance and Depth, float) or .png (tone-mapped sRGB)");
  render->add_option("--png", options.Png, "PNG file (tone-mapped sRGB)");
  render->add_option("--camera", options.Camera, "Camera of the scene (default: the first)");
  render->add_option("--size", options.Size, "Image size WIDTHxHEIGHT (default: the camera's)");
  render->add_option("--spp", options.SamplesPerPixel, "Samples per pixel (default 4)")
    ->check(CLI::Range(1, 4096));
  render->add_option(
    "--exposure", options.Exposure, "Radiance scale before tone mapping, > 0 (default 1)");
  render
    ->add_option("--max-samples",
      options.MaxSamples,
      "Budget of width x height x spp rays (default 2^30, about 18 minutes on one core); a "
      "larger image is refused before solving")
    ->check(CLI::Range(1.0, 1e18));
  render->add_option("--solution",
    options.SolutionFile,
    "A solution written by `sphcover solve -o` (.vtm): only render, no solving");
  render->add_option("--report", options.Report, "Report file (.json), with timings_s.render");
  render->add_option("--fill", options.Fill, "R-buffer fill: projection (default) or raycasting")
    ->check(CLI::IsMember({ "projection", "raycasting" }));
  render->add_option(
    "--set", options.Settings, "Override a setting of the scene file (see subdivide)");

  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    return app.exit(e);
  }

  // Before any thread starts: an interrupted run leaves no partial output behind.
  sphcover_cli::WatchTerminationSignals();

  // ParaView's VTK selects the Sequential SMP backend unless told otherwise (SPEC §2).
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
    if (info->parsed())
    {
      status = RunInfo(options);
    }
    else if (subdivide->parsed())
    {
      status = RunSubdivide(options);
    }
    else if (solve->parsed())
    {
      status = RunSolve(options);
    }
    else if (render->parsed())
    {
      status = RunRender(options);
    }
  }
  catch (const std::exception& e)
  {
    std::cerr << "sphcover: error: " << e.what() << std::endl;
    status = 1;
  }
  const std::string messages = vtkMessages->GetOutput();
  if (status == 0 && !messages.empty())
  {
    std::cerr << messages << std::flush;
  }
  vtkOutputWindow::SetInstance(nullptr);
  return status;
}
