// SPDX-License-Identifier: BSD-3-Clause
#include "reflectance/ReflectanceWeights.h"

#include "math/Constants.h"

#include "cover/HemisphereGrid.h"
#include "reflectance/Reflectance.h"

#include <glm/common.hpp>
#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sphcover
{
namespace
{

/// w per (rowOut, rowIn, deltaColumn) while the table is built, in the layout the private
/// builders of ReflectanceWeights read: (rowOut * rows + rowIn) * columns + deltaColumn.
struct WeightGrid
{
  WeightGrid(std::size_t rows, std::size_t columns)
    : Rows(rows)
    , Columns(columns)
    , Values(rows * rows * columns, glm::dvec3(0.0))
  {
  }
  glm::dvec3& operator()(std::size_t ro, std::size_t ri, std::size_t d)
  {
    return this->Values[(ro * this->Rows + ri) * this->Columns + d];
  }
  const glm::dvec3& operator()(std::size_t ro, std::size_t ri, std::size_t d) const
  {
    return this->Values[(ro * this->Rows + ri) * this->Columns + d];
  }

  const std::size_t Rows;
  const std::size_t Columns;
  std::vector<glm::dvec3> Values;
};

/// The polar sub-directions of every row, Samples per row: cos and sin of theta, row r's at
/// [r * Samples, (r + 1) * Samples).
struct RowSubdirections
{
  int Samples = 0;
  std::vector<double> Cos;
  std::vector<double> Sin;
};

/// Polar angles at the midpoints of `samples` strata of equal projected solid angle (uniform in
/// s = sin^2 theta), as the grid's own samples.
RowSubdirections SubdirectionsOfRows(const HemisphereGrid& grid, int samples)
{
  const std::size_t rows = static_cast<std::size_t>(grid.ThetaBins());
  RowSubdirections sub;
  sub.Samples = samples;
  sub.Cos.resize(rows * samples);
  sub.Sin.resize(rows * samples);
  for (std::size_t r = 0; r < rows; ++r)
  {
    const double s0 = std::pow(std::sin(grid.RowTheta(static_cast<int>(r))), 2);
    const double s1 = std::pow(std::sin(grid.RowTheta(static_cast<int>(r) + 1)), 2);
    for (int k = 0; k < samples; ++k)
    {
      const double s = s0 + (k + 0.5) * (s1 - s0) / samples;
      sub.Sin[r * samples + k] = std::sqrt(s);
      sub.Cos[r * samples + k] = std::sqrt(std::max(0.0, 1.0 - s));
    }
  }
  return sub;
}

/// Per row, the directional albedo a(o) - k_d averaged over the row's sub-directions: what the
/// table's weights toward an out cell of the row sum to.
std::vector<glm::dvec3> TableAlbedos(const Reflectance& reflectance, const RowSubdirections& sub)
{
  const int samples = sub.Samples;
  const std::size_t rows = sub.Cos.size() / static_cast<std::size_t>(samples);
  std::vector<glm::dvec3> albedos(rows, glm::dvec3(0.0));
  for (std::size_t r = 0; r < rows; ++r)
  {
    for (int k = 0; k < samples; ++k)
    {
      // The Lambertian part k_d is not in the table (the propagation shoots it in closed form).
      albedos[r] +=
        (reflectance.Albedo(std::atan2(sub.Sin[r * samples + k], sub.Cos[r * samples + k])) -
          reflectance.LambertianReflectance()) /
        static_cast<double>(samples);
    }
  }
  return albedos;
}

/// The delta of paper §3.5.1: everything from the mirror cell, scaled by k_s; the albedo of
/// every row is k_s.
void PlaceMirrorWeights(const Reflectance& reflectance,
  WeightGrid& w,
  std::vector<glm::dvec3>& albedos)
{
  const std::size_t columns = w.Columns;
  for (std::size_t r = 0; r < w.Rows; ++r)
  {
    if (columns % 2 == 0)
    {
      w(r, r, columns / 2) = reflectance.SpecularReflectance();
    }
    else
    {
      w(r, r, columns / 2) += 0.5 * reflectance.SpecularReflectance();
      w(r, r, (columns / 2 + 1) % columns) += 0.5 * reflectance.SpecularReflectance();
    }
    albedos[r] = reflectance.SpecularReflectance();
  }
}

/// w0(o, c): f - k_d / pi averaged over Samples x Samples in-directions of c times Samples x
/// Samples out-directions of o.
void SampleWeights(const Reflectance& reflectance,
  const HemisphereGrid& grid,
  const RowSubdirections& sub,
  WeightGrid& w)
{
  const int samples = sub.Samples;
  const glm::dvec3 lambertian = reflectance.LambertianReflectance() / Pi;
  const double dphi = grid.PhiStep();
  const double perSample = 1.0 / std::pow(static_cast<double>(samples), 4);
  std::vector<glm::dvec3> outDirections(static_cast<std::size_t>(samples * samples));
  for (std::size_t ro = 0; ro < w.Rows; ++ro)
  {
    for (int k = 0; k < samples; ++k)
    {
      for (int q = 0; q < samples; ++q)
      {
        const double phi = (q + 0.5) * dphi / samples;
        outDirections[static_cast<std::size_t>(k * samples + q)] =
          glm::dvec3(sub.Sin[ro * samples + k] * std::cos(phi),
            sub.Sin[ro * samples + k] * std::sin(phi),
            sub.Cos[ro * samples + k]);
      }
    }
    for (std::size_t ri = 0; ri < w.Rows; ++ri)
    {
      for (std::size_t d = 0; d < w.Columns; ++d)
      {
        glm::dvec3 sum(0.0);
        for (int k = 0; k < samples; ++k)
        {
          for (int q = 0; q < samples; ++q)
          {
            const double phi = (static_cast<double>(d) + (q + 0.5) / samples) * dphi;
            const glm::dvec3 in(sub.Sin[ri * samples + k] * std::cos(phi),
              sub.Sin[ri * samples + k] * std::sin(phi),
              sub.Cos[ri * samples + k]);
            for (const glm::dvec3& out : outDirections)
            {
              sum += reflectance.Evaluate(in, out);
              sum -= lambertian;
            }
          }
        }
        w(ro, ri, d) = sum * perSample;
      }
    }
  }
}

/// Discrete reciprocity: the mean of the table and its transpose (a reciprocal BRDF is
/// symmetric up to rounding; a measured table need not be).
void MakeReciprocal(WeightGrid& w)
{
  const std::size_t columns = w.Columns;
  for (std::size_t ro = 0; ro < w.Rows; ++ro)
  {
    for (std::size_t ri = ro; ri < w.Rows; ++ri)
    {
      for (std::size_t d = 0; d < columns; ++d)
      {
        const std::size_t back = (columns - d) % columns;
        const glm::dvec3 mean = 0.5 * (w(ro, ri, d) + w(ri, ro, back));
        w(ro, ri, d) = mean;
        w(ri, ro, back) = mean;
      }
    }
  }
}

/// Evenness in the column difference: the models are f(delta_phi) = f(-delta_phi)
/// (Reflectance, BrdfTable), and the samples of the column differences d and -d are mirror
/// images, so w(d) = w(-d) up to rounding; made exact, it makes the table's Fourier
/// transform real (Reflect).
void MakeEvenInColumnDifference(WeightGrid& w)
{
  const std::size_t columns = w.Columns;
  for (std::size_t ro = 0; ro < w.Rows; ++ro)
  {
    for (std::size_t ri = 0; ri < w.Rows; ++ri)
    {
      for (std::size_t d = 1; 2 * d < columns; ++d)
      {
        const glm::dvec3 mean = 0.5 * (w(ro, ri, d) + w(ro, ri, columns - d));
        w(ro, ri, d) = mean;
        w(ro, ri, columns - d) = mean;
      }
    }
  }
}

/// Weights below `cutoff` of the largest are dropped (paper §5.2 (ii): "there may be large
/// number of grid cells with 0 weights in the reflectance map table"): whole row pairs then
/// drop out of the shots. They carry a negligible share; the scaling restores the albedo
/// exactly.
void DropBelowCutoff(WeightGrid& w, double cutoff)
{
  glm::dvec3 largest(0.0);
  for (const glm::dvec3& v : w.Values)
  {
    largest = glm::max(largest, v);
  }
  for (glm::dvec3& v : w.Values)
  {
    for (int b = 0; b < 3; ++b)
    {
      if (v[b] < cutoff * largest[b])
      {
        v[b] = 0.0;
      }
    }
  }
}

/// The symmetric scaling per band (Sinkhorn): s_ro sum_ri s_ri Omega_ri K(ro, ri) = albedo(ro),
/// with K(ro, ri) = sum_d w0(ro, ri, d).
std::vector<glm::dvec3> SymmetricScales(const WeightGrid& w,
  const HemisphereGrid& grid,
  const std::vector<glm::dvec3>& albedos)
{
  const std::size_t rows = w.Rows;
  std::vector<glm::dvec3> kernel(rows * rows, glm::dvec3(0.0));
  for (std::size_t ro = 0; ro < rows; ++ro)
  {
    for (std::size_t ri = 0; ri < rows; ++ri)
    {
      for (std::size_t d = 0; d < w.Columns; ++d)
      {
        kernel[ro * rows + ri] += w(ro, ri, d);
      }
      kernel[ro * rows + ri] *= grid.CellMeasure(static_cast<int>(ri));
    }
  }
  std::vector<glm::dvec3> scale(rows, glm::dvec3(1.0));
  for (int iteration = 0; iteration < 1000; ++iteration)
  {
    double worst = 0.0;
    std::vector<glm::dvec3> next(scale);
    for (std::size_t ro = 0; ro < rows; ++ro)
    {
      glm::dvec3 row(0.0);
      for (std::size_t ri = 0; ri < rows; ++ri)
      {
        row += kernel[ro * rows + ri] * scale[ri];
      }
      row *= scale[ro];
      for (int b = 0; b < 3; ++b)
      {
        if (row[b] > 0.0 && albedos[ro][b] > 0.0)
        {
          worst = std::max(worst, std::fabs(row[b] / albedos[ro][b] - 1.0));
          next[ro][b] = scale[ro][b] * std::sqrt(albedos[ro][b] / row[b]);
        }
        else if (albedos[ro][b] <= 0.0)
        {
          next[ro][b] = 0.0;
        }
      }
    }
    scale = next;
    if (worst < 1e-13)
    {
      break;
    }
  }
  return scale;
}

/// w(o, c) = s_row(o) s_row(c) Omega_c w0(o, c); returns max over rows and bands of |s - 1|
/// (LargestScaling), rows without albedo left out.
double ApplyScales(const std::vector<glm::dvec3>& scale,
  const std::vector<glm::dvec3>& albedos,
  const HemisphereGrid& grid,
  WeightGrid& w)
{
  double scaling = 0.0;
  for (std::size_t ro = 0; ro < w.Rows; ++ro)
  {
    for (int b = 0; b < 3; ++b)
    {
      if (albedos[ro][b] > 0.0)
      {
        scaling = std::max(scaling, std::fabs(scale[ro][b] - 1.0));
      }
    }
    for (std::size_t ri = 0; ri < w.Rows; ++ri)
    {
      const glm::dvec3 factor = scale[ro] * scale[ri] * grid.CellMeasure(static_cast<int>(ri));
      for (std::size_t d = 0; d < w.Columns; ++d)
      {
        w(ro, ri, d) *= factor;
      }
    }
  }
  return scaling;
}

/// The rows of `incident` (rows x columns) with some non-zero radiance, into `lit`.
void FindLitRows(const std::vector<glm::dvec3>& incident,
  std::size_t rows,
  std::size_t columns,
  std::vector<std::size_t>& lit)
{
  lit.clear();
  for (std::size_t r = 0; r < rows; ++r)
  {
    const glm::dvec3* row = incident.data() + r * columns;
    if (std::any_of(row, row + columns, [](const glm::dvec3& e) { return e != glm::dvec3(0.0); }))
    {
      lit.push_back(r);
    }
  }
}

/// One direct term of a row pair: out[co] += w e[(co + d) mod columns] for every out column
/// co, the wrap taken out of the loop.
void AddDirectTerm(glm::dvec3* out,
  const glm::dvec3* e,
  std::size_t columns,
  std::size_t d,
  const glm::dvec3& w)
{
  for (std::size_t co = 0; co + d < columns; ++co)
  {
    out[co] += w * e[co + d];
  }
  for (std::size_t co = columns - d; co < columns; ++co)
  {
    out[co] += w * e[co + d - columns];
  }
}

} // namespace

ReflectanceWeights::ReflectanceWeights(const Reflectance& reflectance,
  const HemisphereGrid& grid,
  int samples)
  : Rows(grid.ThetaBins())
  , Columns(grid.PhiBins())
  , Stride(static_cast<std::size_t>(2 * grid.PhiBins() + 2))
{
  if (samples < 1 || samples > 8)
  {
    throw std::invalid_argument("ReflectanceWeights: samples must be in [1, 8]");
  }
  WeightGrid w(static_cast<std::size_t>(this->Rows), static_cast<std::size_t>(this->Columns));
  const RowSubdirections sub = SubdirectionsOfRows(grid, samples);
  this->Albedos = TableAlbedos(reflectance, sub);
  if (reflectance.IsIdealMirror())
  {
    PlaceMirrorWeights(reflectance, w, this->Albedos);
  }
  else
  {
    SampleWeights(reflectance, grid, sub, w);
    MakeReciprocal(w);
    MakeEvenInColumnDifference(w);
    DropBelowCutoff(w, Cutoff);
    const std::vector<glm::dvec3> scale = SymmetricScales(w, grid, this->Albedos);
    this->Scaling = ApplyScales(scale, this->Albedos, grid, w);
  }
  this->BuildCumulativeSums(w.Values);
  this->BuildReflectForm(w.Values);
}

void ReflectanceWeights::BuildCumulativeSums(const std::vector<glm::dvec3>& w)
{
  const std::size_t rows = static_cast<std::size_t>(this->Rows);
  const std::size_t columns = static_cast<std::size_t>(this->Columns);
  auto at = [&](std::size_t ro, std::size_t ri, std::size_t d) -> const glm::dvec3&
  { return w[(ro * rows + ri) * columns + d]; };
  this->Sums.assign(rows * rows * this->Stride, glm::dvec3(0.0));
  this->Coupled.assign(rows * rows, 0);
  for (std::size_t ro = 0; ro < rows; ++ro)
  {
    for (std::size_t ri = 0; ri < rows; ++ri)
    {
      glm::dvec3* c2 = this->Sums.data() + (ro * rows + ri) * this->Stride;
      glm::dvec3 c1(0.0);
      c2[0] = glm::dvec3(0.0);
      for (std::size_t t = 0; t + 1 < this->Stride; ++t)
      {
        // c1 = C1[t] = sum_{m < t} w[m mod PhiBins]; C2[t + 1] = C2[t] + C1[t].
        c2[t + 1] = c2[t] + c1;
        if (t < 2 * columns)
        {
          c1 += at(ro, ri, t % columns);
        }
      }
      bool coupled = false;
      for (std::size_t d = 0; d < columns; ++d)
      {
        const glm::dvec3& v = at(ro, ri, d);
        coupled = coupled || v.x != 0.0 || v.y != 0.0 || v.z != 0.0;
      }
      this->Coupled[ro * rows + ri] = coupled ? 1 : 0;
    }
  }
}

void ReflectanceWeights::BuildReflectForm(const std::vector<glm::dvec3>& w)
{
  const std::size_t rows = static_cast<std::size_t>(this->Rows);
  const std::size_t columns = static_cast<std::size_t>(this->Columns);
  auto at = [&](std::size_t ro, std::size_t ri, std::size_t d) -> const glm::dvec3&
  { return w[(ro * rows + ri) * columns + d]; };
  this->SpectrumLength = this->Columns / 2 + 1;
  const std::size_t length = static_cast<std::size_t>(this->SpectrumLength);
  this->DirectOffsets.assign(rows * rows + 1, 0);
  this->SpectrumOf.assign(rows * rows, -1);
  this->InRowSpectral.assign(rows, 0);
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  std::vector<double> line(columns);
  std::vector<std::complex<double>> spectrum(length);
  for (std::size_t ro = 0; ro < rows; ++ro)
  {
    for (std::size_t ri = 0; ri < rows; ++ri)
    {
      const std::size_t pair = ro * rows + ri;
      std::size_t nonZero = 0;
      for (std::size_t d = 0; d < columns; ++d)
      {
        nonZero += at(ro, ri, d) != glm::dvec3(0.0) ? 1 : 0;
      }
      if (nonZero <= static_cast<std::size_t>(DirectTerms))
      {
        for (std::size_t d = 0; d < columns; ++d)
        {
          if (at(ro, ri, d) != glm::dvec3(0.0))
          {
            this->Directs.push_back({ static_cast<int>(d), at(ro, ri, d) });
          }
        }
      }
      else
      {
        // I(co) = sum_d w(d) e(co + d) is a correlation: its DFT is conj(W(k)) E(k), and W is
        // real because w is even in d (MakeEvenInColumnDifference; the mirror's delta is even
        // as well).
        this->SpectrumOf[pair] = static_cast<int>(this->Spectra.size() / (3 * length));
        this->InRowSpectral[ri] = 1;
        for (int b = 0; b < 3; ++b)
        {
          for (std::size_t d = 0; d < columns; ++d)
          {
            line[d] = at(ro, ri, d)[b];
          }
          fft.fwd(spectrum.data(), line.data(), static_cast<Eigen::Index>(columns));
          for (const std::complex<double>& value : spectrum)
          {
            this->Spectra.push_back(value.real());
          }
        }
      }
      this->DirectOffsets[pair + 1] = this->Directs.size();
    }
  }
}

void ReflectanceWeights::Reflect(const std::vector<glm::dvec3>& incident,
  std::vector<glm::dvec3>& exitant) const
{
  Scratch scratch;
  this->Reflect(incident, exitant, scratch);
}

void ReflectanceWeights::Reflect(const std::vector<glm::dvec3>& incident,
  std::vector<glm::dvec3>& exitant,
  Scratch& scratch) const
{
  const std::size_t rows = static_cast<std::size_t>(this->Rows);
  const std::size_t columns = static_cast<std::size_t>(this->Columns);
  const std::size_t length = static_cast<std::size_t>(this->SpectrumLength);
  exitant.assign(rows * columns, glm::dvec3(0.0));
  std::vector<std::size_t>& lit = scratch.Lit;
  FindLitRows(incident, rows, columns, lit);
  if (lit.empty())
  {
    return;
  }
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::HalfSpectrum);
  std::vector<double>& line = scratch.Line;
  line.resize(columns);
  // The transforms of the lit in rows, per band.
  std::vector<std::complex<double>>& in = scratch.In;
  in.resize(rows * 3 * length);
  for (std::size_t ri : lit)
  {
    if (!this->InRowSpectral[ri])
    {
      continue;
    }
    for (int b = 0; b < 3; ++b)
    {
      for (std::size_t c = 0; c < columns; ++c)
      {
        line[c] = incident[ri * columns + c][b];
      }
      fft.fwd(&in[(ri * 3 + static_cast<std::size_t>(b)) * length],
        line.data(),
        static_cast<Eigen::Index>(columns));
    }
  }
  std::vector<std::complex<double>>& sum = scratch.Sum;
  sum.resize(3 * length);
  for (std::size_t ro = 0; ro < rows; ++ro)
  {
    glm::dvec3* out = exitant.data() + ro * columns;
    bool spectral = false;
    std::fill(sum.begin(), sum.end(), std::complex<double>(0.0));
    for (std::size_t ri : lit)
    {
      const std::size_t pair = ro * rows + ri;
      const int index = this->SpectrumOf[pair];
      if (index >= 0)
      {
        spectral = true;
        const double* w = &this->Spectra[static_cast<std::size_t>(index) * 3 * length];
        const std::complex<double>* e = &in[ri * 3 * length];
        for (std::size_t k = 0; k < 3 * length; ++k)
        {
          sum[k] += w[k] * e[k];
        }
        continue;
      }
      const glm::dvec3* e = incident.data() + ri * columns;
      for (std::size_t t = this->DirectOffsets[pair]; t < this->DirectOffsets[pair + 1]; ++t)
      {
        AddDirectTerm(out,
          e,
          columns,
          static_cast<std::size_t>(this->Directs[t].Delta),
          this->Directs[t].Weight);
      }
    }
    if (spectral)
    {
      for (int b = 0; b < 3; ++b)
      {
        fft.inv(line.data(),
          &sum[static_cast<std::size_t>(b) * length],
          static_cast<Eigen::Index>(columns));
        for (std::size_t co = 0; co < columns; ++co)
        {
          out[co][b] += line[co];
        }
      }
    }
  }
  for (glm::dvec3& value : exitant)
  {
    value = glm::max(value, glm::dvec3(0.0));
  }
}

glm::dvec3 ReflectanceWeights::Weight(int rowOut, int rowIn, int deltaColumn) const
{
  const glm::dvec3* c2 = this->Cumulative(rowOut, rowIn);
  return this->FirstSum(c2, deltaColumn + 1) - this->FirstSum(c2, deltaColumn);
}

glm::dvec3 ReflectanceWeights::StripWeight(int rowOut,
  int columnOut,
  int rowIn,
  int begin,
  int end) const
{
  const glm::dvec3* c2 = this->Cumulative(rowOut, rowIn);
  const int p = this->Columns;
  return this->FirstSum(c2, end - columnOut + p) - this->FirstSum(c2, begin - columnOut + p);
}

glm::dvec3 ReflectanceWeights::StripPairWeight(int rowOut,
  int outBegin,
  int outEnd,
  int rowIn,
  int begin,
  int end) const
{
  // sum_{o in [ob, oe)} (C1[end - o + P] - C1[begin - o + P]) and
  // sum_{o in [ob, oe)} C1[x - o] = C2[x - ob + 1] - C2[x - oe + 1].
  const glm::dvec3* c2 = this->Cumulative(rowOut, rowIn);
  const int xe = end + this->Columns;
  const int xb = begin + this->Columns;
  return (c2[xe - outBegin + 1] - c2[xe - outEnd + 1]) -
    (c2[xb - outBegin + 1] - c2[xb - outEnd + 1]);
}

glm::dvec3 ReflectanceWeights::RowWeight(int rowOut, int rowIn) const
{
  return this->FirstSum(this->Cumulative(rowOut, rowIn), this->Columns);
}

std::size_t ReflectanceWeights::MemoryBytes() const
{
  return this->Sums.size() * sizeof(glm::dvec3) + this->Coupled.size() +
    this->Albedos.size() * sizeof(glm::dvec3);
}

std::size_t ReflectanceWeights::EstimateBytes(int thetaBins, int phiBins)
{
  const std::size_t rowPairs = static_cast<std::size_t>(thetaBins) * thetaBins;
  const std::size_t columns = static_cast<std::size_t>(phiBins);
  // w and Sums (Stride 2 columns + 2) as dvec3, the spectra as 3 real doubles per frequency.
  return rowPairs *
    ((columns + 2 * columns + 2) * sizeof(glm::dvec3) + (columns / 2 + 1) * 3 * sizeof(double));
}

} // namespace sphcover
