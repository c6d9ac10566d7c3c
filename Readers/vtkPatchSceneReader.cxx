// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPatchSceneReader.h"

#include "vtkSceneCameras.h"
#include "vtkSceneFileLoader.h"
#include "vtkScenePieces.h"
#include "vtkSphericalCoverArrayNames.h"
#include "vtkSurfaceGridBuilder.h"

#include "scene/Scene.h"

#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationDataObjectMetaDataKey.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkUnstructuredGrid.h>

#include <exception>
#include <filesystem>
#include <utility>

namespace names = vtkSphericalCoverArrayNames;

vtkStandardNewMacro(vtkPatchSceneReader);

struct vtkPatchSceneReader::LoadedScene
{
  std::string FileName;
  std::filesystem::file_time_type Modified;
  sphcover::Scene Scene;
};

namespace
{
/// The file's modification time, or the epoch when it cannot be read (then no cache matches).
std::filesystem::file_time_type ModificationTime(const std::string& path)
{
  std::error_code error;
  const auto time = std::filesystem::last_write_time(path, error);
  return error ? std::filesystem::file_time_type() : time;
}
}

vtkPatchSceneReader::vtkPatchSceneReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkPatchSceneReader::~vtkPatchSceneReader() = default;

sphcover::Scene vtkPatchSceneReader::LoadFile(const std::string& fileName)
{
  return vtkSceneFileLoader::Load(fileName);
}

int vtkPatchSceneReader::RequestInformation(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  // The reader answers every piece request itself (the whole scene to piece 0, nothing to the
  // others) instead of leaving pieces > 0 to the executive's default.
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);

  // The cameras, before any data exists: vtkRadianceImageFilter's image size is that of a
  // scene camera and must be known when it announces its extent. A file that does not load
  // publishes none; RequestData reports its error (one message, where it was before).
  outInfo->Remove(vtkSceneCameras::SCENE_CAMERAS());
  this->Loaded.reset();
  if (!this->FileName.empty())
  {
    try
    {
      const std::filesystem::file_time_type modified = ModificationTime(this->FileName);
      sphcover::Scene scene = this->LoadFile(this->FileName);
      vtkNew<vtkUnstructuredGrid> described;
      vtkSurfaceGridBuilder::AddFieldData(scene, described);
      vtkNew<vtkDataObject> cameras;
      cameras->GetFieldData()->AddArray(
        described->GetFieldData()->GetAbstractArray(names::CameraNames));
      cameras->GetFieldData()->AddArray(
        described->GetFieldData()->GetArray(names::CameraParameters));
      outInfo->Set(vtkSceneCameras::SCENE_CAMERAS(), cameras);
      this->Loaded.reset(new LoadedScene{ this->FileName, modified, std::move(scene) });
    }
    catch (const std::exception&)
    {
      // Reported by RequestData.
    }
  }
  return 1;
}

int vtkPatchSceneReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  output->Initialize();
  // The scene RequestInformation read, if it is still the file's (taken: read once).
  std::unique_ptr<LoadedScene> loaded = std::move(this->Loaded);
  if (vtkScenePieces::RequestedPiece(outputVector) > 0)
  {
    // Global illumination needs the whole scene in one piece: piece 0 has it (vtkScenePieces.h).
    return 1;
  }
  if (this->FileName.empty())
  {
    vtkErrorMacro("No FileName was set.");
    return 0;
  }
  this->UpdateProgress(0.0);
  try
  {
    const bool current = loaded && loaded->FileName == this->FileName &&
      loaded->Modified != std::filesystem::file_time_type() &&
      loaded->Modified == ModificationTime(this->FileName);
    const sphcover::Scene scene =
      current ? std::move(loaded->Scene) : this->LoadFile(this->FileName);
    this->UpdateProgress(0.5);
    vtkSurfaceGridBuilder::Build(scene, output);
  }
  catch (const std::exception& e)
  {
    // Nothing partial: the output stays empty and the request fails.
    output->Initialize();
    vtkErrorMacro(<< e.what());
    return 0;
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPatchSceneReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName.empty() ? "(none)" : this->FileName) << "\n";
}
