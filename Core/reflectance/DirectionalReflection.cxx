// SPDX-License-Identifier: BSD-3-Clause
#include "reflectance/DirectionalReflection.h"

#include "cover/HemisphereGrid.h"
#include "cover/SphericalCover.h"

#include <algorithm>

namespace sphcover
{

bool SameReflectance(const Material& a, const Material& b)
{
  return a.Type == b.Type && a.Diffuse == b.Diffuse && a.Specular == b.Specular &&
    a.PhongExponent == b.PhongExponent && a.TableFile == b.TableFile && a.Table == b.Table;
}

glm::dvec3 DirectionalExitantRadiance(const SphericalCover& cover,
  const ReflectanceWeights& table,
  std::size_t point,
  const std::vector<glm::dvec3>& incident,
  const glm::dvec3& localDirection)
{
  const int cell = cover.Grid().CellOfLocalDirection(localDirection);
  if (cell < 0 || !(localDirection.z > 0.0))
  {
    return glm::dvec3(0.0);
  }
  return DirectionalExitantRadianceOfCell(cover, table, point, incident, cell);
}

glm::dvec3 DirectionalExitantRadianceOfCell(const SphericalCover& cover,
  const ReflectanceWeights& table,
  std::size_t point,
  const std::vector<glm::dvec3>& incident,
  int cell)
{
  const HemisphereGrid& grid = cover.Grid();
  if (cell < 0 || cell >= grid.CellCount())
  {
    return glm::dvec3(0.0);
  }
  const int rowOut = grid.RowOfCell(cell);
  const int columnOut = grid.ColumnOfCell(cell);
  glm::dvec3 sum(0.0);
  for (std::size_t e = cover.EntryBegin(point); e < cover.EntryEnd(point); ++e)
  {
    glm::dvec3 weight(0.0);
    for (std::size_t k = cover.StripBegin(e); k < cover.StripEnd(e); ++k)
    {
      const SphericalCover::Strip& strip = cover.StripAt(k);
      if (table.RowsCoupled(rowOut, strip.Row))
      {
        weight += table.StripWeight(rowOut, columnOut, strip.Row, strip.PhiBegin, strip.PhiEnd);
      }
    }
    sum += weight * incident[e];
  }
  return sum;
}

PointReflectances::PointReflectances(const HemisphereGrid& grid,
  const std::vector<Material>& materialOfPoint)
{
  this->ModelOfPoint.assign(materialOfPoint.size(), -1);
  std::vector<const Material*> distinct;
  for (std::size_t i = 0; i < materialOfPoint.size(); ++i)
  {
    const Material& material = materialOfPoint[i];
    if (material.Type == MaterialType::Diffuse)
    {
      continue;
    }
    std::size_t k = 0;
    while (k < distinct.size() && !SameReflectance(*distinct[k], material))
    {
      ++k;
    }
    if (k == distinct.size())
    {
      distinct.push_back(&material);
      this->Models.emplace_back(material);
      this->Tables.emplace_back(this->Models.back(), grid);
    }
    this->ModelOfPoint[i] = static_cast<int>(k);
  }
}

std::size_t PointReflectances::EstimateBytes(int thetaBins,
  int phiBins,
  const std::vector<Material>& materialOfPoint)
{
  // The same count of distinct reflectances as the constructor's.
  std::vector<const Material*> distinct;
  for (const Material& material : materialOfPoint)
  {
    if (material.Type != MaterialType::Diffuse &&
      std::none_of(distinct.begin(),
        distinct.end(),
        [&](const Material* other) { return SameReflectance(*other, material); }))
    {
      distinct.push_back(&material);
    }
  }
  return distinct.size() * ReflectanceWeights::EstimateBytes(thetaBins, phiBins);
}

const Reflectance* PointReflectances::Model(std::size_t point) const
{
  const int k = this->ModelOfPoint[point];
  return k < 0 ? nullptr : &this->Models[static_cast<std::size_t>(k)];
}

const ReflectanceWeights* PointReflectances::Table(std::size_t point) const
{
  const int k = this->ModelOfPoint[point];
  return k < 0 ? nullptr : &this->Tables[static_cast<std::size_t>(k)];
}

} // namespace sphcover
