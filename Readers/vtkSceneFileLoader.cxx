// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSceneFileLoader.h"

#include "InputError.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>

namespace
{
void RecordError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* message = static_cast<std::string*>(clientData);
  if (message->empty() && callData)
  {
    *message = static_cast<const char*>(callData);
    // VTK's messages end with a blank line; keep one line.
    while (!message->empty() && std::isspace(static_cast<unsigned char>(message->back())))
    {
      message->pop_back();
    }
  }
}

std::string LowerExtension(const std::string& path)
{
  const size_t dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? std::string() : path.substr(dot + 1);
  std::transform(
    ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}
}

std::vector<sphcover::MeshFace> vtkSceneFileLoader::ReadMeshFaces(const std::string& path)
{
  const std::string ext = LowerExtension(path);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == "obj")
  {
    auto obj = vtkSmartPointer<vtkOBJReader>::New();
    obj->SetFileName(path.c_str());
    reader = obj;
  }
  else if (ext == "ply")
  {
    auto ply = vtkSmartPointer<vtkPLYReader>::New();
    ply->SetFileName(path.c_str());
    reader = ply;
  }
  else if (ext == "vtp")
  {
    auto vtp = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    vtp->SetFileName(path.c_str());
    reader = vtp;
  }
  else
  {
    throw sphcover::InputError(
      path, "", "unsupported mesh format '." + ext + "' (use .obj, .ply or .vtp)");
  }

  // VTK readers report problems through the error event, not by return values.
  std::string error;
  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(RecordError);
  onError->SetClientData(&error);
  reader->AddObserver(vtkCommand::ErrorEvent, onError);
  reader->AddObserver(vtkCommand::WarningEvent, onError);
  reader->Update();
  vtkPolyData* mesh = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!error.empty() || !mesh)
  {
    throw sphcover::InputError(
      path, "", "cannot read mesh: " + (error.empty() ? std::string("no output") : error));
  }
  if (mesh->GetNumberOfLines() > 0 || mesh->GetNumberOfStrips() > 0)
  {
    throw sphcover::InputError(
      path, "", "only triangles and quads are supported (the mesh has lines or strips)");
  }

  std::vector<sphcover::MeshFace> faces;
  faces.reserve(static_cast<size_t>(mesh->GetNumberOfPolys()));
  auto polys = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
  {
    vtkIdType size = 0;
    const vtkIdType* ids = nullptr;
    polys->GetCurrentCell(size, ids);
    sphcover::MeshFace face(static_cast<size_t>(size));
    for (vtkIdType k = 0; k < size; ++k)
    {
      mesh->GetPoint(ids[k], &face[static_cast<size_t>(k)][0]);
    }
    faces.push_back(std::move(face));
  }
  return faces;
}

sphcover::Scene vtkSceneFileLoader::Load(const std::string& path)
{
  const std::string ext = LowerExtension(path);
  if (ext == "bpt")
  {
    return sphcover::LoadBptAsScene(path);
  }
  return sphcover::LoadSceneFile(path, &vtkSceneFileLoader::ReadMeshFaces);
}
