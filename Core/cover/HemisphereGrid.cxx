// SPDX-License-Identifier: BSD-3-Clause
#include "cover/HemisphereGrid.h"

#include "math/Constants.h"

#include "subdivision/Patch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace sphcover
{

namespace
{

/// v minus its component along the unit vector n.
glm::dvec3 Orthogonalised(const glm::dvec3& v, const glm::dvec3& n)
{
  return v - glm::dot(v, n) * n;
}
}

HemisphereFrame HemisphereFrame::FromPartials(const glm::dvec3& origin,
  const glm::dvec3& normal,
  const glm::dvec3& partialU,
  const glm::dvec3& partialV)
{
  HemisphereFrame frame;
  frame.Origin = origin;
  frame.Normal = glm::normalize(normal);
  const glm::dvec3& n = frame.Normal;
  // A projection shorter than this fraction of the vector's own length is rounding noise (the
  // vector is parallel to N, or zero).
  constexpr double negligible = 1e-9;
  glm::dvec3 tangent = Orthogonalised(partialU, n);
  if (!(glm::length(tangent) > negligible * glm::length(partialU)) || glm::length(partialU) == 0.0)
  {
    tangent = glm::cross(partialV, n);
    if (!(glm::length(tangent) > negligible * glm::length(partialV)) ||
      glm::length(partialV) == 0.0)
    {
      const glm::dvec3 axes[3] = { { 1.0, 0.0, 0.0 }, { 0.0, 1.0, 0.0 }, { 0.0, 0.0, 1.0 } };
      int best = 0;
      for (int k = 1; k < 3; ++k)
      {
        if (std::fabs(glm::dot(axes[k], n)) < std::fabs(glm::dot(axes[best], n)))
        {
          best = k;
        }
      }
      tangent = Orthogonalised(axes[best], n);
    }
  }
  frame.Tangent = glm::normalize(tangent);
  frame.Bitangent = glm::cross(n, frame.Tangent);
  return frame;
}

HemisphereFrame HemisphereFrame::OfPatch(const Patch& patch)
{
  return FromPartials(patch.Point,
    patch.Normal,
    patch.Geometry.PartialU(0.5, 0.5),
    patch.Geometry.PartialV(0.5, 0.5));
}

glm::dvec3 HemisphereFrame::ToLocal(const glm::dvec3& world) const
{
  return {
    glm::dot(world, this->Tangent), glm::dot(world, this->Bitangent), glm::dot(world, this->Normal)
  };
}

glm::dvec3 HemisphereFrame::ToWorld(const glm::dvec3& local) const
{
  return local.x * this->Tangent + local.y * this->Bitangent + local.z * this->Normal;
}

void HemisphereGrid::CheckSizes(int thetaBins, int phiBins, int samplesTheta, int samplesPhi)
{
  if (thetaBins < 1 || thetaBins > 65535 || phiBins < 1 || phiBins > 65535)
  {
    throw std::invalid_argument(
      "HemisphereGrid: ThetaBins and PhiBins must be in [1, 65535], got " +
      std::to_string(thetaBins) + " x " + std::to_string(phiBins));
  }
  if (static_cast<long long>(thetaBins) * phiBins > std::numeric_limits<int>::max())
  {
    throw std::invalid_argument("HemisphereGrid: " + std::to_string(thetaBins) + " x " +
      std::to_string(phiBins) + " cells are more than int cell indices can count");
  }
  if (samplesTheta < 1 || samplesTheta > 16 || samplesPhi < 1 || samplesPhi > 16)
  {
    throw std::invalid_argument("HemisphereGrid: samples per cell must be in [1, 16] x [1, 16], "
                                "got " +
      std::to_string(samplesTheta) + " x " + std::to_string(samplesPhi));
  }
}

HemisphereGrid::HemisphereGrid(int thetaBins, int phiBins, int samplesTheta, int samplesPhi)
  : ThetaBinCount(thetaBins)
  , PhiBinCount(phiBins)
  , SamplesThetaCount(samplesTheta)
  , SamplesPhiCount(samplesPhi)
{
  CheckSizes(thetaBins, phiBins, samplesTheta, samplesPhi);
  this->DeltaTheta = HalfPi / thetaBins;
  this->DeltaPhi = TwoPi / phiBins;

  this->RowMeasures.resize(static_cast<size_t>(thetaBins));
  for (int row = 0; row < thetaBins; ++row)
  {
    const double t0 = this->RowTheta(row);
    const double t1 = this->RowTheta(row + 1);
    // (cos 2t0 - cos 2t1) / 4 = sin(t1 - t0) sin(t1 + t0) / 2, without the cancellation of the
    // difference of cosines in narrow rows.
    this->RowMeasures[static_cast<size_t>(row)] =
      this->DeltaPhi * std::sin(t1 - t0) * std::sin(t1 + t0) / 2.0;
  }

  // Sample rows: midpoints of equal strata of s = sin^2 theta. cos^2 is interpolated from its
  // own ends so that neither sin nor cos loses accuracy near the pole or the horizon.
  this->SampleCos.resize(static_cast<size_t>(this->SampleRows()));
  this->SampleSin.resize(static_cast<size_t>(this->SampleRows()));
  for (int row = 0; row < thetaBins; ++row)
  {
    const double s0 = std::pow(std::sin(this->RowTheta(row)), 2);
    const double s1 = std::pow(std::sin(this->RowTheta(row + 1)), 2);
    const double c0 = std::pow(std::cos(this->RowTheta(row)), 2);
    const double c1 = row + 1 == thetaBins ? 0.0 : std::pow(std::cos(this->RowTheta(row + 1)), 2);
    for (int a = 0; a < samplesTheta; ++a)
    {
      const double fraction = (a + 0.5) / samplesTheta;
      const size_t k = static_cast<size_t>(row * samplesTheta + a);
      this->SampleSin[k] = std::sqrt(s0 + fraction * (s1 - s0));
      this->SampleCos[k] = std::sqrt(c0 + fraction * (c1 - c0));
    }
  }
  this->ColumnCos.resize(static_cast<size_t>(this->SampleColumns()));
  this->ColumnSin.resize(static_cast<size_t>(this->SampleColumns()));
  for (int column = 0; column < this->SampleColumns(); ++column)
  {
    const double phi = this->SamplePhi(column);
    this->ColumnCos[static_cast<size_t>(column)] = std::cos(phi);
    this->ColumnSin[static_cast<size_t>(column)] = std::sin(phi);
  }

  // The edges as CellOfAngles draws them: theta = r DeltaTheta, phi = c DeltaPhi.
  for (int row = 0; row <= thetaBins; ++row)
  {
    this->RowEdgeCos.push_back(std::cos(row * this->DeltaTheta));
    this->RowEdgeSin.push_back(std::sin(row * this->DeltaTheta));
  }
  for (int column = 0; column <= phiBins; ++column)
  {
    this->ColumnEdgeCos.push_back(std::cos(column * this->DeltaPhi));
    this->ColumnEdgeSin.push_back(std::sin(column * this->DeltaPhi));
  }

  // Order of the samples from the cell centre, in coordinates normalised to the unit square.
  this->CentreOrder.resize(static_cast<size_t>(this->SamplesPerCell()));
  std::iota(this->CentreOrder.begin(), this->CentreOrder.end(), 0);
  auto distance = [samplesTheta, samplesPhi](int k)
  {
    const double x = (k / samplesPhi + 0.5) / samplesTheta - 0.5;
    const double y = (k % samplesPhi + 0.5) / samplesPhi - 0.5;
    return x * x + y * y;
  };
  std::stable_sort(this->CentreOrder.begin(),
    this->CentreOrder.end(),
    [&distance](int a, int b) { return distance(a) < distance(b); });
}

double HemisphereGrid::RowTheta(int row) const
{
  return row == this->ThetaBinCount ? HalfPi : row * this->DeltaTheta;
}

double HemisphereGrid::TotalMeasure() const
{
  double sum = 0.0;
  for (const double m : this->RowMeasures)
  {
    sum += m;
  }
  return sum * this->PhiBinCount;
}

glm::dvec3 HemisphereGrid::LocalDirection(double theta, double phi)
{
  const double s = std::sin(theta);
  return { s * std::cos(phi), s * std::sin(phi), std::cos(theta) };
}

void HemisphereGrid::LocalAngles(const glm::dvec3& local, double& theta, double& phi)
{
  theta = std::atan2(std::hypot(local.x, local.y), local.z);
  phi = std::atan2(local.y, local.x);
  if (phi < 0.0)
  {
    phi += TwoPi;
  }
  if (phi >= TwoPi)
  {
    phi = 0.0;
  }
}

int HemisphereGrid::CellOfAngles(double theta, double phi) const
{
  if (!(theta >= 0.0 && theta <= HalfPi) || !std::isfinite(phi))
  {
    return -1;
  }
  phi = std::fmod(phi, TwoPi);
  if (phi < 0.0)
  {
    phi += TwoPi;
  }
  const int row = std::min(static_cast<int>(theta / this->DeltaTheta), this->ThetaBinCount - 1);
  const int column = std::min(static_cast<int>(phi / this->DeltaPhi), this->PhiBinCount - 1);
  return this->CellIndex(row, column);
}

int HemisphereGrid::CellOfLocalDirection(const glm::dvec3& local) const
{
  // The directional part of the render (paper §5.3.1) looks the eye's cell up per stencil point
  // and sample: by the edges' (sin, cos) instead of two atan2 (and a hypot). A direction at the
  // angle a from an edge at the angle e has cross product |d| sin(a - e) with the edge's unit
  // vector, so its sign says on which side the direction lies; farther than `margin` from both
  // edges of the cell found, the rounding of atan2 and of CellOfAngles' division (a few 1e-16
  // rad) cannot put the direction in another cell, so the cell is that of the atan2 path.
  constexpr double margin = 1e-9;
  auto byAngles = [&]
  {
    double theta;
    double phi;
    LocalAngles(local, theta, phi);
    return this->CellOfAngles(theta, phi);
  };
  const double rxy = std::sqrt(local.x * local.x + local.y * local.y);
  const double length = std::sqrt(rxy * rxy + local.z * local.z);
  if (!(local.z > margin * length) || !(rxy > margin * length) || !std::isfinite(length))
  {
    // Near the pole (phi undefined), near or below the tangent plane, or not finite.
    return byAngles();
  }
  // Row: the last edge r with theta >= r DeltaTheta, i.e. sin(theta - e_r) >= 0:
  // rxy cos e_r - z sin e_r >= 0 (every theta and e_r in [0, pi/2], so the sign is monotone).
  auto rowSide = [&](int r)
  {
    return rxy * this->RowEdgeCos[static_cast<size_t>(r)] -
      local.z * this->RowEdgeSin[static_cast<size_t>(r)];
  };
  int low = 0;                    // rowSide(0) = rxy > 0
  int high = this->ThetaBinCount; // rowSide(ThetaBins) = -z < 0
  while (high - low > 1)
  {
    const int middle = (low + high) / 2;
    (rowSide(middle) >= 0.0 ? low : high) = middle;
  }
  const int row = low;
  // Column: phi in (0, pi) when y > 0, in (pi, 2 pi) when y < 0; the edges searched lie in the
  // same half turn plus its ends, so sin(phi - e_c) = (y cos e_c - x sin e_c) / rxy is monotone
  // in c there.
  auto columnSide = [&](int c)
  {
    return local.y * this->ColumnEdgeCos[static_cast<size_t>(c)] -
      local.x * this->ColumnEdgeSin[static_cast<size_t>(c)];
  };
  if (!(std::fabs(local.y) > margin * rxy))
  {
    // Near phi = 0 or pi: an edge of the half turns.
    return byAngles();
  }
  // The edges from phi = 0 to the first at or beyond pi (y > 0), or from the last at or below
  // pi to 2 pi (y < 0).
  const int first = local.y > 0.0 ? 0 : this->PhiBinCount / 2;
  const int last = local.y > 0.0 ? (this->PhiBinCount + 1) / 2 : this->PhiBinCount;
  // Within half a turn of every edge searched but perhaps the ends (an odd PhiBins puts one
  // just past pi): columnSide(first) >= 0 > columnSide(last) is checked, else the atan2 path.
  if (!(columnSide(first) >= 0.0) || !(columnSide(last) < 0.0))
  {
    return byAngles();
  }
  low = first;
  high = last;
  while (high - low > 1)
  {
    const int middle = (low + high) / 2;
    (columnSide(middle) >= 0.0 ? low : high) = middle;
  }
  const int column = low;
  if (!(rowSide(row) > margin * length) || !(-rowSide(row + 1) > margin * length) ||
    !(columnSide(column) > margin * rxy) || !(-columnSide(column + 1) > margin * rxy))
  {
    // Within the margin of an edge: the atan2 path's rounding decides.
    return byAngles();
  }
  return this->CellIndex(row, column);
}

glm::dvec3 HemisphereGrid::CellCentreDirection(int cell) const
{
  const int row = this->RowOfCell(cell);
  const int column = this->ColumnOfCell(cell);
  return LocalDirection((row + 0.5) * this->DeltaTheta, (column + 0.5) * this->DeltaPhi);
}

glm::dvec3 HemisphereGrid::SampleDirection(int sampleRow, int sampleColumn) const
{
  const double s = this->SampleSin[static_cast<size_t>(sampleRow)];
  return { s * this->ColumnCos[static_cast<size_t>(sampleColumn)],
    s * this->ColumnSin[static_cast<size_t>(sampleColumn)],
    this->SampleCos[static_cast<size_t>(sampleRow)] };
}

void HemisphereGrid::SampleColumnsIn(double phiBegin, double phiEnd, int& first, int& last) const
{
  // Column c has phi = (c + 1/2) h; it lies in [phiBegin, phiEnd) iff
  // phiBegin / h - 1/2 <= c < phiEnd / h - 1/2.
  const double h = this->DeltaPhi / this->SamplesPhiCount;
  const int columns = this->SampleColumns();
  first = static_cast<int>(std::ceil(phiBegin / h - 0.5));
  last = static_cast<int>(std::ceil(phiEnd / h - 0.5));
  first = std::max(0, std::min(first, columns));
  last = std::max(first, std::min(last, columns));
}

} // namespace sphcover
