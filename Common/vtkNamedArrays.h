// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkNamedArrays.h
 * @brief New named, sized data arrays: the output arrays every stage builds.
 */
#ifndef vtkNamedArrays_h
#define vtkNamedArrays_h

#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

namespace vtkNamedArrays
{
template<typename ArrayType>
vtkSmartPointer<ArrayType> New(const char* name, int components, vtkIdType tuples)
{
  auto array = vtkSmartPointer<ArrayType>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

inline vtkSmartPointer<vtkIntArray> Int(const char* name, int components, vtkIdType tuples)
{
  return New<vtkIntArray>(name, components, tuples);
}

inline vtkSmartPointer<vtkDoubleArray> Double(const char* name, int components, vtkIdType tuples)
{
  return New<vtkDoubleArray>(name, components, tuples);
}

inline vtkSmartPointer<vtkStringArray> String(const char* name, vtkIdType values)
{
  return New<vtkStringArray>(name, 1, values);
}
}

#endif
