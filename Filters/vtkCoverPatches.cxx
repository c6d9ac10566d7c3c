// SPDX-License-Identifier: BSD-3-Clause
#include "vtkCoverPatches.h"

#include "vtkSphericalCoverFilter.h"

#include <vtkAlgorithm.h>
#include <vtkDataSet.h>
#include <vtkInformationVector.h>

vtkDataSet* vtkCoverPatches::Find(vtkAlgorithm* self, vtkInformationVector** inputVector)
{
  if (self->GetNumberOfInputConnections(1) > 0)
  {
    return vtkDataSet::GetData(inputVector[1], 0);
  }
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
