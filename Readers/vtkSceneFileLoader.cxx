// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSceneFileLoader.h"

#include "scene/InputError.h"
#include "scene/InputFile.h"
#include "scene/MeshFileCheck.h"

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

#include <cctype>
#include <new>
#include <stdexcept>

namespace
{
/// VTK's message is "ERROR: In <source>, line <n>\n<class> (<address>): <text>\n\n": the
/// user can act on <text> alone, and the rule is one line, so whitespace runs become a space.
void RecordError(vtkObject*, unsigned long, void* clientData, void* callData)
{
  auto* message = static_cast<std::string*>(clientData);
  if (!message->empty() || !callData)
  {
    return;
  }
  std::string text = static_cast<const char*>(callData);
  const size_t newline = text.find('\n');
  const size_t origin = newline == std::string::npos ? newline : text.find("): ", newline);
  if (origin != std::string::npos)
  {
    text = text.substr(origin + 3);
  }
  for (const char c : text)
  {
    if (!std::isspace(static_cast<unsigned char>(c)))
    {
      *message += c;
    }
    else if (!message->empty() && message->back() != ' ')
    {
      *message += ' ';
    }
  }
  while (!message->empty() && message->back() == ' ')
  {
    message->pop_back();
  }
}
}

std::vector<sphcover::MeshFace> vtkSceneFileLoader::ReadMeshFaces(const std::string& path)
{
  // The file policy and the counts and indices VTK's readers would trust (MeshFileCheck.h).
  sphcover::CheckMeshFile(path);
  const std::string ext = sphcover::LowerExtension(path);
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
  try
  {
    reader->Update();
  }
  catch (const std::bad_alloc&)
  {
    // Whatever the checks missed: one line naming the file, not "std::bad_alloc".
    throw sphcover::InputError(path, "", "cannot read mesh: out of memory");
  }
  catch (const std::length_error& e)
  {
    throw sphcover::InputError(path, "", std::string("cannot read mesh: ") + e.what());
  }
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
  const std::string ext = sphcover::LowerExtension(path);
  if (ext == "bpt")
  {
    return sphcover::LoadBptAsScene(path);
  }
  return sphcover::LoadSceneFile(path, &vtkSceneFileLoader::ReadMeshFaces);
}
