// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCoverPatches.h"

#include "vtkSphericalCoverFilter.h"

#include <vtkAlgorithm.h>
#include <vtkDataSet.h>
#include <vtkInformationVector.h>

namespace
{
/// The input of the nearest vtkSphericalCoverFilter up port 0's chain of first inputs.
vtkDataSet* UpstreamCoverInput(vtkAlgorithm* self)
{
  // Follow the first input of every stage up from the illumination; a pipeline is a few stages
  // deep, the bound only stops a cycle a broken pipeline could hold.
  vtkAlgorithm* algorithm =
    self->GetNumberOfInputConnections(0) > 0 ? self->GetInputAlgorithm(0, 0) : nullptr;
  for (int depth = 0; algorithm && depth < 64; ++depth)
  {
    if (vtkSphericalCoverFilter::SafeDownCast(algorithm))
    {
      return vtkDataSet::SafeDownCast(algorithm->GetInputDataObject(0, 0));
    }
    algorithm =
      algorithm->GetNumberOfInputPorts() > 0 && algorithm->GetNumberOfInputConnections(0) > 0
      ? algorithm->GetInputAlgorithm(0, 0)
      : nullptr;
  }
  return nullptr;
}
}

vtkDataSet* vtkCoverPatches::Find(vtkAlgorithm* self, vtkInformationVector** inputVector)
{
  if (self->GetNumberOfInputConnections(1) > 0)
  {
    return vtkDataSet::GetData(inputVector[1], 0);
  }
  return UpstreamCoverInput(self);
}

vtkDataSet* vtkCoverPatches::Find(vtkAlgorithm* self)
{
  if (self->GetNumberOfInputPorts() > 1 && self->GetNumberOfInputConnections(1) > 0)
  {
    return vtkDataSet::SafeDownCast(self->GetInputDataObject(1, 0));
  }
  return UpstreamCoverInput(self);
}
