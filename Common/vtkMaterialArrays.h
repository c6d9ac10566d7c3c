// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkMaterialArrays
 * @brief Turns the material arrays of a dataset back into sphcover::Material (paper §3.5.1),
 * one tuple at a time: the one reading shared by the surface grids (cell data, read by
 * vtkSurfaceGridAdapter) and the characteristic points (point data, read by
 * vtkIlluminationAdapter for the propagation and rendering filters). vtkSurfaceGridBuilder
 * writes the arrays (Documentation/Pipeline.md#reader).
 *
 * Arrays of the attribute set: `Diffuse`, `Emission` (3 components, required), `MaterialType`
 * (missing: diffuse), `Specular` (3), `PhongExponent` (required for a non-diffuse material),
 * `MaterialId`; of the field data: `MaterialNames` and `MaterialFiles` (the BRDF table of a
 * tabulated material), indexed by MaterialId.
 */
#ifndef vtkMaterialArrays_h
#define vtkMaterialArrays_h

#include "SphericalCoverCommonModule.h" // for export macro

#include "scene/Material.h" // for the material

#include <vtkType.h> // for vtkIdType

#include <string> // for the error

class vtkDataArray;
class vtkDataSetAttributes;
class vtkFieldData;
class vtkStringArray;

class SPHERICALCOVERCOMMON_EXPORT vtkMaterialArrays
{
public:
  /// The arrays of `attributes` (point or cell data) and `fieldData`; `element` names a tuple
  /// in messages ("point", "cell").
  vtkMaterialArrays(vtkDataSetAttributes* attributes, vtkFieldData* fieldData, const char* element);

  /// Whether Diffuse and Emission are there with 3 components (and Specular, when present);
  /// otherwise false with one sentence in `error`.
  bool Check(std::string& error) const;

  /// The MaterialId of tuple `i` (-1 without the array).
  vtkIdType MaterialId(vtkIdType i) const;

  /// The material of tuple `i` (after a successful Check). False with one sentence in `error`
  /// for an unknown MaterialType, a non-diffuse material without Specular and PhongExponent,
  /// or a tabulated material without a table file.
  bool Read(vtkIdType i, sphcover::Material& material, std::string& error) const;

private:
  std::string Element;
  vtkDataArray* Diffuse;
  vtkDataArray* Emission;
  vtkDataArray* Type;
  vtkDataArray* Specular;
  vtkDataArray* Exponent;
  vtkDataArray* Id;
  vtkStringArray* Names;
  vtkStringArray* Files;
};

#endif
