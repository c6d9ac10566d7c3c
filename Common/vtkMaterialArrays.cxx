// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMaterialArrays.h"

#include "vtkSphericalCoverArrayNames.h"

#include <vtkDataArray.h>
#include <vtkDataSetAttributes.h>
#include <vtkFieldData.h>
#include <vtkStringArray.h>

#include <cmath>
#include <sstream>

namespace names = vtkSphericalCoverArrayNames;

namespace
{
vtkStringArray* StringArray(vtkFieldData* fieldData, const char* name)
{
  return vtkStringArray::SafeDownCast(fieldData ? fieldData->GetAbstractArray(name) : nullptr);
}
}

vtkMaterialArrays::vtkMaterialArrays(vtkDataSetAttributes* attributes,
  vtkFieldData* fieldData,
  const char* element)
  : Element(element)
  , Diffuse(attributes->GetArray(names::Diffuse))
  , Emission(attributes->GetArray(names::Emission))
  , Type(attributes->GetArray(names::MaterialType))
  , Specular(attributes->GetArray(names::Specular))
  , Exponent(attributes->GetArray(names::PhongExponent))
  , Id(attributes->GetArray(names::MaterialId))
  , Names(StringArray(fieldData, names::MaterialNames))
  , Files(StringArray(fieldData, names::MaterialFiles))
  , Transmittance(attributes->GetArray(names::Transmittance))
  , Textures(StringArray(fieldData, names::MaterialTextures))
  , TextureEncodings(StringArray(fieldData, names::MaterialTextureEncodings))
{
}

bool vtkMaterialArrays::Check(std::string& error) const
{
  if (!this->Diffuse || !this->Emission || this->Diffuse->GetNumberOfComponents() != 3 ||
    this->Emission->GetNumberOfComponents() != 3)
  {
    error =
      "the " + this->Element + "s lack the material arrays Diffuse and Emission (3 components)";
    return false;
  }
  if (this->Transmittance && this->Transmittance->GetNumberOfComponents() != 3)
  {
    error = "the Transmittance array of the " + this->Element + "s must have 3 components";
    return false;
  }
  if (this->Specular && this->Specular->GetNumberOfComponents() != 3)
  {
    error = "the Specular array of the " + this->Element + "s must have 3 components";
    return false;
  }
  return true;
}

vtkIdType vtkMaterialArrays::MaterialId(vtkIdType i) const
{
  return this->Id ? static_cast<vtkIdType>(this->Id->GetComponent(i, 0)) : -1;
}

bool vtkMaterialArrays::Read(vtkIdType i, sphcover::Material& material, std::string& error) const
{
  const std::string where = this->Element + " " + std::to_string(i);
  material = sphcover::Material();
  const double kind = this->Type ? this->Type->GetComponent(i, 0) : 0.0;
  if (!(kind >= 0.0 && kind <= static_cast<double>(sphcover::MaterialType::Tabulated)) ||
    kind != std::floor(kind))
  {
    std::ostringstream value;
    value << kind;
    error = where + " has the unknown MaterialType " + value.str() +
      " (0 diffuse, 1 mirror, 2 phong, 3 tabulated)";
    return false;
  }
  material.Type = static_cast<sphcover::MaterialType>(static_cast<int>(kind));
  this->Diffuse->GetTuple(i, &material.Diffuse[0]);
  this->Emission->GetTuple(i, &material.Emission[0]);
  if (material.Type != sphcover::MaterialType::Diffuse && (!this->Specular || !this->Exponent))
  {
    error = where + " has a " + sphcover::MaterialTypeName(material.Type) + " material but the " +
      this->Element + "s lack the Specular and PhongExponent arrays";
    return false;
  }
  if (this->Specular)
  {
    this->Specular->GetTuple(i, &material.Specular[0]);
  }
  if (this->Exponent)
  {
    material.PhongExponent = this->Exponent->GetComponent(i, 0);
  }
  const vtkIdType id = this->MaterialId(i);
  if (this->Names && id >= 0 && id < this->Names->GetNumberOfValues())
  {
    material.Name = this->Names->GetValue(id);
  }
  if (material.Type == sphcover::MaterialType::Tabulated)
  {
    if (!this->Files || id < 0 || id >= this->Files->GetNumberOfValues() ||
      this->Files->GetValue(id).empty())
    {
      error = where +
        " has a tabulated material but no BRDF table file (MaterialId and the MaterialFiles "
        "field array)";
      return false;
    }
    material.TableFile = this->Files->GetValue(id);
  }
  if (this->Transmittance)
  {
    this->Transmittance->GetTuple(i, &material.Transmittance[0]);
  }
  return this->ReadTexture(id, material, error);
}

bool vtkMaterialArrays::ReadTexture(vtkIdType id,
  sphcover::Material& material,
  std::string& error) const
{
  if (!this->Textures || id < 0 || id >= this->Textures->GetNumberOfValues() ||
    this->Textures->GetValue(id).empty())
  {
    return true;
  }
  material.TextureFile = this->Textures->GetValue(id);
  const bool linear = this->TextureEncodings && id < this->TextureEncodings->GetNumberOfValues() &&
    this->TextureEncodings->GetValue(id) == "linear";
  material.TextureFileEncoding =
    linear ? sphcover::TextureEncoding::Linear : sphcover::TextureEncoding::Srgb;
  auto found = this->TexturesRead.find(id);
  if (found == this->TexturesRead.end())
  {
    try
    {
      found = this->TexturesRead
                .emplace(id,
                  std::make_shared<const sphcover::Texture>(
                    sphcover::Texture::Load(material.TextureFile, material.TextureFileEncoding)))
                .first;
    }
    catch (const std::exception& e)
    {
      error = std::string("material ") + std::to_string(id) + "'s texture: " + e.what();
      return false;
    }
  }
  material.DiffuseTexture = found->second;
  return true;
}
