// SPDX-License-Identifier: BSD-3-Clause
#include "Scene.h"

#include <glm/common.hpp>

#include <limits>

namespace sphcover
{

const char* MaterialTypeName(MaterialType type)
{
  switch (type)
  {
    case MaterialType::Diffuse:
      return "diffuse";
    case MaterialType::Mirror:
      return "mirror";
    case MaterialType::Phong:
      return "phong";
    case MaterialType::Tabulated:
      return "tabulated";
  }
  return "unknown";
}

void Scene::Bounds(glm::dvec3& lower, glm::dvec3& upper) const
{
  lower = glm::dvec3(std::numeric_limits<double>::infinity());
  upper = glm::dvec3(-std::numeric_limits<double>::infinity());
  for (const Surface& surface : this->Surfaces)
  {
    for (const glm::dvec3& p : surface.Patch.ControlPoints())
    {
      lower = glm::min(lower, p);
      upper = glm::max(upper, p);
    }
  }
}

int Scene::FindMaterial(const std::string& name) const
{
  for (size_t m = 0; m < this->Materials.size(); ++m)
  {
    if (this->Materials[m].Name == name)
    {
      return static_cast<int>(m);
    }
  }
  return -1;
}

} // namespace sphcover
