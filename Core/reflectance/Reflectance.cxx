// SPDX-License-Identifier: BSD-3-Clause
#include "reflectance/Reflectance.h"

#include "math/Constants.h"

#include "scene/BrdfTable.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sphcover
{
namespace
{
/// Nodes in theta and azimuths over [0, pi] of the phong normalization (file comment).
constexpr int LobeNodes = 128;
constexpr int LobeAzimuths = 256;

void CheckBands(const glm::dvec3& v, const Material& material, const char* what)
{
  for (int b = 0; b < 3; ++b)
  {
    if (!(v[b] >= 0.0 && v[b] <= 1.0))
    {
      throw std::invalid_argument(
        "Reflectance: " + std::string(what) + " of material '" + material.Name + "' not in [0, 1]");
    }
  }
}

/// max(0, c)^n with 0^0 taken as 0 (the lobe ends at 90 degrees from the mirror direction).
double Lobe(double cosAlpha, double n)
{
  return cosAlpha > 0.0 ? std::pow(cosAlpha, n) : 0.0;
}

/// Linear interpolation of node values at theta_k = (k + 1/2) (pi / 2) / size, clamped at the
/// ends.
double InterpolateInTheta(const std::vector<double>& nodes, double theta)
{
  const double x = theta / (0.5 * Pi) * static_cast<double>(nodes.size()) - 0.5;
  if (x <= 0.0)
  {
    return nodes.front();
  }
  if (x >= static_cast<double>(nodes.size() - 1))
  {
    return nodes.back();
  }
  const std::size_t k = static_cast<std::size_t>(x);
  const double t = x - static_cast<double>(k);
  return (1.0 - t) * nodes[k] + t * nodes[k + 1];
}
}

Reflectance::Reflectance(const Material& material)
  : Type(material.Type)
{
  switch (material.Type)
  {
    case MaterialType::Diffuse:
      CheckBands(material.Diffuse, material, "reflectance");
      this->KDiffuse = material.Diffuse;
      break;
    case MaterialType::Mirror:
      CheckBands(material.Specular, material, "reflectance");
      this->KSpecular = material.Specular;
      break;
    case MaterialType::Phong:
      CheckBands(material.Diffuse, material, "diffuse reflectance");
      CheckBands(material.Specular, material, "specular reflectance");
      CheckBands(material.Diffuse + material.Specular, material, "diffuse + specular");
      if (!(material.PhongExponent >= 0.0 && std::isfinite(material.PhongExponent)))
      {
        throw std::invalid_argument(
          "Reflectance: exponent of material '" + material.Name + "' negative or not finite");
      }
      this->KDiffuse = material.Diffuse;
      this->KSpecular = material.Specular;
      this->Exponent = material.PhongExponent;
      this->NormalizeLobe();
      break;
    case MaterialType::Tabulated:
      this->Table = material.Table
        ? material.Table
        : std::make_shared<const BrdfTable>(BrdfTable::Load(material.TableFile));
      this->AlbedoByDegree.resize(91);
      for (int degree = 0; degree <= 90; ++degree)
      {
        this->AlbedoByDegree[static_cast<std::size_t>(degree)] =
          this->Table->Albedo(degree * Pi / 180.0);
      }
      break;
  }
}

void Reflectance::NormalizeLobe()
{
  // The lobe's kernel between node a (out) and node b (in), integrated over the azimuth
  // difference: k_ab = integral_0^{2 pi} max(0, cos alpha)^n dphi, symmetric in a and b, and
  // the measure mu_b = sin(theta_b) cos(theta_b) dtheta of node b (midpoint rule in theta).
  const std::size_t m = LobeNodes;
  const double step = 0.5 * Pi / LobeNodes;
  std::vector<double> cosTheta(m), sinTheta(m), measure(m);
  for (std::size_t k = 0; k < m; ++k)
  {
    const double theta = (static_cast<double>(k) + 0.5) * step;
    sinTheta[k] = std::sin(theta);
    cosTheta[k] = std::cos(theta);
    measure[k] = sinTheta[k] * cosTheta[k] * step;
  }
  std::vector<double> cosPhi(LobeAzimuths);
  for (int p = 0; p < LobeAzimuths; ++p)
  {
    cosPhi[static_cast<std::size_t>(p)] = std::cos((p + 0.5) * Pi / LobeAzimuths);
  }
  std::vector<double> kernel(m * m, 0.0);
  for (std::size_t a = 0; a < m; ++a)
  {
    for (std::size_t b = a; b < m; ++b)
    {
      double sum = 0.0;
      for (double cp : cosPhi)
      {
        // cos alpha = in . mirror(out) = cos a cos b - sin a sin b cos(dphi).
        sum += Lobe(cosTheta[a] * cosTheta[b] - sinTheta[a] * sinTheta[b] * cp, this->Exponent);
      }
      // Over [0, pi] and doubled: the lobe is even in dphi.
      kernel[a * m + b] = kernel[b * m + a] = 2.0 * sum * Pi / LobeAzimuths;
    }
  }
  // Symmetric Sinkhorn scaling: find c_a > 0 with c_a sum_b k_ab mu_b c_b = 1 for every a.
  // The iteration c_a <- c_a / sqrt(row sum) converges for a positive symmetric kernel; the
  // start is the normal-incidence normalization sqrt((n + 2) / (2 pi)).
  this->LobeScale.assign(m, std::sqrt((this->Exponent + 2.0) / (2.0 * Pi)));
  std::vector<double> next(m);
  for (int iteration = 0; iteration < 2000; ++iteration)
  {
    double worst = 0.0;
    for (std::size_t a = 0; a < m; ++a)
    {
      double row = 0.0;
      for (std::size_t b = 0; b < m; ++b)
      {
        row += kernel[a * m + b] * measure[b] * this->LobeScale[b];
      }
      row *= this->LobeScale[a];
      worst = std::max(worst, std::fabs(row - 1.0));
      next[a] = row > 0.0 ? this->LobeScale[a] / std::sqrt(row) : this->LobeScale[a];
    }
    this->LobeScale.swap(next);
    if (worst < 1e-12)
    {
      break;
    }
  }
}

double Reflectance::LobeNormalization(double theta) const
{
  if (this->LobeScale.empty())
  {
    return 1.0;
  }
  return InterpolateInTheta(this->LobeScale, theta);
}

glm::dvec3 Reflectance::Evaluate(const glm::dvec3& in, const glm::dvec3& out) const
{
  if (in.z <= 0.0 || out.z <= 0.0)
  {
    return glm::dvec3(0.0);
  }
  switch (this->Type)
  {
    case MaterialType::Diffuse:
      return this->KDiffuse / Pi;
    case MaterialType::Mirror:
      return glm::dvec3(0.0);
    case MaterialType::Phong:
    {
      const double cosAlpha = glm::dot(in, MirrorDirection(out));
      const double lobe = Lobe(cosAlpha, this->Exponent) *
        InterpolateInTheta(this->LobeScale, std::acos(std::min(1.0, in.z))) *
        InterpolateInTheta(this->LobeScale, std::acos(std::min(1.0, out.z)));
      return this->KDiffuse / Pi + this->KSpecular * lobe;
    }
    case MaterialType::Tabulated:
    {
      const double thetaIn = std::acos(std::min(1.0, in.z));
      const double thetaOut = std::acos(std::min(1.0, out.z));
      const double deltaPhi = std::atan2(out.y, out.x) - std::atan2(in.y, in.x);
      return this->Table->Evaluate(thetaIn, thetaOut, deltaPhi);
    }
  }
  return glm::dvec3(0.0);
}

glm::dvec3 Reflectance::Evaluate(double thetaIn, double thetaOut, double deltaPhi) const
{
  if (this->Type == MaterialType::Tabulated)
  {
    if (thetaIn >= 0.5 * Pi || thetaOut >= 0.5 * Pi)
    {
      return glm::dvec3(0.0);
    }
    return this->Table->Evaluate(thetaIn, thetaOut, deltaPhi);
  }
  const glm::dvec3 in(std::sin(thetaIn), 0.0, std::cos(thetaIn));
  const glm::dvec3 out(std::sin(thetaOut) * std::cos(deltaPhi),
    std::sin(thetaOut) * std::sin(deltaPhi),
    std::cos(thetaOut));
  return this->Evaluate(in, out);
}

glm::dvec3 Reflectance::Albedo(double theta) const
{
  switch (this->Type)
  {
    case MaterialType::Diffuse:
      return this->KDiffuse;
    case MaterialType::Mirror:
      return this->KSpecular;
    case MaterialType::Phong:
      return this->KDiffuse + this->KSpecular;
    case MaterialType::Tabulated:
    {
      const double degree = std::clamp(theta * 180.0 / Pi, 0.0, 90.0);
      const std::size_t k = std::min<std::size_t>(89, static_cast<std::size_t>(degree));
      const double t = degree - static_cast<double>(k);
      return (1.0 - t) * this->AlbedoByDegree[k] + t * this->AlbedoByDegree[k + 1];
    }
  }
  return glm::dvec3(0.0);
}

} // namespace sphcover
