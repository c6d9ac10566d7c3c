// SPDX-License-Identifier: BSD-3-Clause
#include "cover/HemisphereInterpolation.h"

#include "subdivision/CharacteristicPointInterpolator.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace sphcover
{

namespace
{
enum class Role : uint8_t
{
  Undecided,
  Key,
  Interpolated
};

/// The point whose patch holds (u, v) on `surface`, or -1 outside the unit square.
std::ptrdiff_t PointAt(const CharacteristicPointInterpolator& layout,
  int surface,
  double u,
  double v)
{
  if (!(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0))
  {
    return -1;
  }
  return layout.ContainingPoint(surface, u, v);
}
}

namespace
{
/// A run of one source along a theta row: columns [Begin, End).
struct Run
{
  int32_t Source;
  int Begin;
  int End;
  float Depth;
};

void RowRuns(const int32_t* sources, const float* depths, int columns, std::vector<Run>& runs)
{
  runs.clear();
  for (int c = 0; c < columns;)
  {
    const int begin = c;
    double depth = 0.0;
    while (c < columns && sources[c] == sources[begin])
    {
      depth += depths[c];
      ++c;
    }
    runs.push_back({ sources[begin], begin, c, static_cast<float>(depth / (c - begin)) });
  }
}

/// The longest common subsequence of the runs' sources: matched (index in a, index in b),
/// ascending; ties prefer to advance in a first, so the result depends on the rows alone.
void Match(const std::vector<Run>& a,
  const std::vector<Run>& b,
  std::vector<uint16_t>& table,
  std::vector<std::pair<int, int>>& matches)
{
  const size_t na = a.size();
  const size_t nb = b.size();
  table.assign((na + 1) * (nb + 1), 0);
  auto at = [&](size_t i, size_t j) -> uint16_t& { return table[i * (nb + 1) + j]; };
  for (size_t i = na; i-- > 0;)
  {
    for (size_t j = nb; j-- > 0;)
    {
      at(i, j) = a[i].Source == b[j].Source ? static_cast<uint16_t>(at(i + 1, j + 1) + 1)
                                            : std::max(at(i + 1, j), at(i, j + 1));
    }
  }
  matches.clear();
  size_t i = 0;
  size_t j = 0;
  while (i < na && j < nb)
  {
    if (a[i].Source == b[j].Source && at(i, j) == at(i + 1, j + 1) + 1)
    {
      matches.emplace_back(static_cast<int>(i), static_cast<int>(j));
      ++i;
      ++j;
    }
    else if (at(i + 1, j) >= at(i, j + 1))
    {
      ++i;
    }
    else
    {
      ++j;
    }
  }
}

/// An interpolated run: [Begin, End) in fractional columns.
struct Piece
{
  int32_t Source;
  double Begin;
  double End;
  float Depth;
};

/// The unmatched runs [first, last) of one row, lying in [from, to) there, scaled into
/// [begin, end).
void PlaceGap(const std::vector<Run>& runs,
  int first,
  int last,
  double from,
  double to,
  double begin,
  double end,
  std::vector<Piece>& pieces)
{
  if (first >= last || to <= from || end <= begin)
  {
    return;
  }
  const double scale = (end - begin) / (to - from);
  for (int k = first; k < last; ++k)
  {
    const Run& run = runs[static_cast<size_t>(k)];
    pieces.push_back({ run.Source,
      begin + (run.Begin - from) * scale,
      begin + (run.End - from) * scale,
      run.Depth });
  }
}
}

void InterpolateHemispheres(int thetaBins,
  int phiBins,
  const int32_t* sourcesA,
  const float* depthsA,
  const int32_t* sourcesB,
  const float* depthsB,
  double t,
  int32_t* sources,
  float* depths)
{
  thread_local std::vector<Run> a;
  thread_local std::vector<Run> b;
  thread_local std::vector<uint16_t> table;
  thread_local std::vector<std::pair<int, int>> matches;
  thread_local std::vector<Piece> pieces;
  auto lerp = [t](double x, double y) { return (1.0 - t) * x + t * y; };
  for (int row = 0; row < thetaBins; ++row)
  {
    const size_t offset = static_cast<size_t>(row) * static_cast<size_t>(phiBins);
    RowRuns(sourcesA + offset, depthsA + offset, phiBins, a);
    RowRuns(sourcesB + offset, depthsB + offset, phiBins, b);
    Match(a, b, table, matches);
    pieces.clear();
    // Between consecutive matched strips (and the row's ends), the gap of each row.
    int previousA = -1;
    int previousB = -1;
    double gapA0 = 0.0;
    double gapB0 = 0.0;
    for (size_t m = 0; m <= matches.size(); ++m)
    {
      const bool last = m == matches.size();
      const int nextA = last ? static_cast<int>(a.size()) : matches[m].first;
      const int nextB = last ? static_cast<int>(b.size()) : matches[m].second;
      const double gapA1 = last ? phiBins : a[static_cast<size_t>(nextA)].Begin;
      const double gapB1 = last ? phiBins : b[static_cast<size_t>(nextB)].Begin;
      const double begin = lerp(gapA0, gapB0);
      const double end = lerp(gapA1, gapB1);
      const double shareA = (1.0 - t) * (gapA1 - gapA0);
      const double shareB = t * (gapB1 - gapB0);
      const double split =
        shareA + shareB > 0.0 ? begin + (end - begin) * shareA / (shareA + shareB) : begin;
      PlaceGap(a, previousA + 1, nextA, gapA0, gapA1, begin, split, pieces);
      PlaceGap(b, previousB + 1, nextB, gapB0, gapB1, split, end, pieces);
      if (last)
      {
        break;
      }
      const Run& ra = a[static_cast<size_t>(nextA)];
      const Run& rb = b[static_cast<size_t>(nextB)];
      pieces.push_back({ ra.Source,
        lerp(ra.Begin, rb.Begin),
        lerp(ra.End, rb.End),
        static_cast<float>(lerp(ra.Depth, rb.Depth)) });
      previousA = nextA;
      previousB = nextB;
      gapA0 = ra.End;
      gapB0 = rb.End;
    }
    // A cell takes the piece that holds its centre; the pieces are in order and tile the row.
    size_t k = 0;
    for (int c = 0; c < phiBins; ++c)
    {
      const double centre = c + 0.5;
      while (k + 1 < pieces.size() && pieces[k].End <= centre)
      {
        ++k;
      }
      sources[offset + static_cast<size_t>(c)] = pieces[k].Source;
      depths[offset + static_cast<size_t>(c)] = pieces[k].Depth;
    }
  }
}

HemisphereInterpolationPlan::HemisphereInterpolationPlan(const std::vector<Patch>& patches,
  const HemisphereInterpolationOptions& options)
{
  const std::size_t count = patches.size();
  this->Offsets.assign(count + 1, 0);
  this->Pairs.assign(count * 4, None);
  if (!options.Enabled || count == 0)
  {
    return;
  }
  const CharacteristicPointInterpolator layout =
    CharacteristicPointInterpolator::OfPatches(patches);
  const double minimumCosine =
    std::cos(options.MaxNormalAngleDegrees * 3.14159265358979323846 / 180.0);
  std::vector<Role> roles(count, Role::Undecided);
  this->Pairs.assign(count * 4, None);
  std::vector<std::vector<uint32_t>> donors(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    if (roles[i] == Role::Key)
    {
      continue;
    }
    const Patch& patch = patches[i];
    const UVRect& r = patch.Domain;
    // Just beyond each edge, at the centre's other parameter: left, right, below, above.
    const double du = 1e-6 * (r.U1 - r.U0);
    const double dv = 1e-6 * (r.V1 - r.V0);
    const std::array<std::ptrdiff_t, 4> around = {
      { PointAt(layout, patch.SurfaceIndex, r.U0 - du, r.CenterV()),
        PointAt(layout, patch.SurfaceIndex, r.U1 + du, r.CenterV()),
        PointAt(layout, patch.SurfaceIndex, r.CenterU(), r.V0 - dv),
        PointAt(layout, patch.SurfaceIndex, r.CenterU(), r.V1 + dv) }
    };
    // Only the complete pairs give donors.
    std::array<std::ptrdiff_t, 4> pairs = around;
    for (int axis = 0; axis < 2; ++axis)
    {
      if (pairs[axis * 2] < 0 || pairs[axis * 2 + 1] < 0)
      {
        pairs[axis * 2] = pairs[axis * 2 + 1] = -1;
      }
    }
    bool usable = pairs[0] >= 0 || pairs[2] >= 0;
    std::vector<uint32_t> chosen;
    const double reach = options.MaxDonorDistance * patch.Geometry.Size();
    for (const std::ptrdiff_t k : pairs)
    {
      if (!usable || k < 0)
      {
        continue;
      }
      const Patch& donor = patches[static_cast<std::size_t>(k)];
      usable = static_cast<std::size_t>(k) != i &&
        roles[static_cast<std::size_t>(k)] != Role::Interpolated &&
        glm::dot(donor.Normal, patch.Normal) >= minimumCosine &&
        glm::length(donor.Point - patch.Point) <= reach;
      chosen.push_back(static_cast<uint32_t>(k));
    }
    if (!usable)
    {
      roles[i] = Role::Key;
      continue;
    }
    for (int k = 0; k < 4; ++k)
    {
      this->Pairs[i * 4 + static_cast<std::size_t>(k)] =
        pairs[k] < 0 ? None : static_cast<uint32_t>(pairs[k]);
    }
    std::sort(chosen.begin(), chosen.end());
    chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
    roles[i] = Role::Interpolated;
    for (const uint32_t k : chosen)
    {
      roles[k] = Role::Key;
    }
    donors[i] = std::move(chosen);
  }
  for (std::size_t i = 0; i < count; ++i)
  {
    this->Offsets[i + 1] = this->Offsets[i] + static_cast<uint32_t>(donors[i].size());
    this->DonorList.insert(this->DonorList.end(), donors[i].begin(), donors[i].end());
    this->Interpolated += donors[i].empty() ? 0 : 1;
  }
}

} // namespace sphcover
