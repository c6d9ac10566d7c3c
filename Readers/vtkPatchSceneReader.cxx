// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPatchSceneReader.h"

#include "vtkSceneFileLoader.h"
#include "vtkScenePieces.h"
#include "vtkSurfaceGridBuilder.h"

#include "scene/Scene.h"

#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkUnstructuredGrid.h>

#include <exception>

vtkStandardNewMacro(vtkPatchSceneReader);

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
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkPatchSceneReader::RequestData(vtkInformation*,
  vtkInformationVector**,
  vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  output->Initialize();
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
    const sphcover::Scene scene = this->LoadFile(this->FileName);
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
