// SPDX-License-Identifier: BSD-3-Clause
#include "vtkBPTReader.h"

#include "scene/Scene.h"
#include "scene/SceneLoader.h"

#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkBPTReader);

vtkBPTReader::vtkBPTReader() = default;

vtkBPTReader::~vtkBPTReader() = default;

sphcover::Scene vtkBPTReader::LoadFile(const std::string& fileName)
{
  return sphcover::LoadBptAsScene(fileName);
}

void vtkBPTReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
