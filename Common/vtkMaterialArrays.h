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
 * `MaterialId`, `Transmittance` (3; missing: opaque); of the field data: `MaterialNames`,
 * `MaterialFiles` (the BRDF table of a tabulated material), `MaterialTextures` and
 * `MaterialTextureEncodings` (the texture PNG and its encoding, paper §5.4), indexed by
 * MaterialId. A texture is read once per material and shared by its tuples.
 */
#ifndef vtkMaterialArrays_h
#define vtkMaterialArrays_h

#include "SphericalCoverCommonModule.h" // for export macro

#include "scene/Material.h" // for the material

#include <vtkType.h> // for vtkIdType

#include <map>    // for the textures read
#include <memory> // for the textures read
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
  /// a tabulated material without a table file, or a texture that cannot be read (the
  /// texture's InputError message).
  bool Read(vtkIdType i, sphcover::Material& material, std::string& error) const;

private:
  /// The texture of material `id` from MaterialTextures, read once; true without one.
  bool ReadTexture(vtkIdType id, sphcover::Material& material, std::string& error) const;

  std::string Element;
  vtkDataArray* Diffuse;
  vtkDataArray* Emission;
  vtkDataArray* Type;
  vtkDataArray* Specular;
  vtkDataArray* Exponent;
  vtkDataArray* Id;
  vtkStringArray* Names;
  vtkStringArray* Files;
  vtkDataArray* Transmittance;
  vtkStringArray* Textures;
  vtkStringArray* TextureEncodings;
  /// The textures read so far, by MaterialId (Read is logically const: a cache).
  mutable std::map<vtkIdType, std::shared_ptr<const sphcover::Texture>> TexturesRead;
};

#endif
