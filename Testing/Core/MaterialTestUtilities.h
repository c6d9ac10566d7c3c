// SPDX-License-Identifier: BSD-3-Clause
// Materials of every reflectance kind (paper §3.5) for Core's propagation tests.
#ifndef SPHCOVER_MATERIALTESTUTILITIES_H
#define SPHCOVER_MATERIALTESTUTILITIES_H

#include "scene/Material.h"

#include <glm/vec3.hpp>

#include <string>

namespace sphcover_test
{
using sphcover::Material;
using sphcover::MaterialType;

inline Material Mirror(const glm::dvec3& ks, const glm::dvec3& le = glm::dvec3(0.0))
{
  Material m;
  m.Name = "mirror";
  m.Type = MaterialType::Mirror;
  m.Specular = ks;
  m.Emission = le;
  return m;
}

inline Material Phong(const glm::dvec3& kd,
  const glm::dvec3& ks,
  double n,
  const glm::dvec3& le = glm::dvec3(0.0))
{
  Material m;
  m.Name = "phong";
  m.Type = MaterialType::Phong;
  m.Diffuse = kd;
  m.Specular = ks;
  m.PhongExponent = n;
  m.Emission = le;
  return m;
}

inline Material Clay(const glm::dvec3& le = glm::dvec3(0.0))
{
  Material m;
  m.Name = "clay";
  m.Type = MaterialType::Tabulated;
  m.TableFile = std::string(SPHCOVER_DATA_DIR) + "/brdf/clay.brdf.csv";
  m.Emission = le;
  return m;
}

inline Material Diffuse(const glm::dvec3& rho, const glm::dvec3& le = glm::dvec3(0.0))
{
  Material m;
  m.Name = "diffuse";
  m.Type = MaterialType::Diffuse;
  m.Diffuse = rho;
  m.Emission = le;
  return m;
}

} // namespace sphcover_test

#endif
