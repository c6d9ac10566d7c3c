// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ReflectanceWeights.h
 * @brief The precomputed weight tables w(out, in-cell) of paper §3.5 ("For A Surface With
 * General Reflectance: I(theta_r, phi_r) = sum_ij w_ij e_ij ... w_ij is precomputed and set up
 * in tables depending on surface properties") over the cells of a HemisphereGrid.
 *
 * The exitant radiance toward out cell o from incident radiance e_c per in-cell c is
 *     I(o) = k_d / pi sum_c Omega_c e_c + sum_c w(o, c) e_c,   w(o, c) ~ (f(c, o) - k_d / pi)
 * Omega_c, Omega_c the cell's projected solid angle: the table holds the BRDF without its
 * Lambertian part k_d (Reflectance::LambertianReflectance, the diffuse part of phong), which the
 * propagation shoots in closed form like a diffuse surface's (paper §5.2). Isotropy makes w depend
 * on the two cells' rows and on the column difference (col_c - col_o) mod PhiBins only, so the
 * table holds ThetaBins^2 x PhiBins values per band instead of cells^2 (32 x 32 x 128 for the
 * default grid: 131072, not 16.8 million).
 *
 * Construction:
 *  - ideal mirror: w(o, c) = k_s for c the mirror cell of o (same row, column + PhiBins/2;
 *    with an odd PhiBins the mirror direction of a cell centre lies on a column boundary and
 *    k_s is split evenly between the two cells);
 *  - otherwise f - k_d / pi is averaged over Samples x Samples in-directions of c times
 *    Samples x Samples out-directions of o (strata of equal projected solid angle, as
 *    HemisphereGrid's samples), made symmetric (w(o, c) / Omega_c = w(c, o) / Omega_o, the
 *    discrete reciprocity) and even in the column difference (as the models are in delta_phi),
 *    cleared below Cutoff times its largest value (paper §5.2 (ii):
 *    "there may be large number of grid cells with 0 weights in the reflectance map table";
 *    row pairs left without weight drop out of the shots: a phong lobe of exponent 40 couples
 *    a row with the rows within about 37 degrees of it) and then scaled per row and band,
 *    w(o, c) = s_row(o) s_row(c) w0(o, c), so that
 *        sum_c w(o, c) = a(o) - k_d,  the BRDF's directional albedo (Reflectance::Albedo)
 *    without its Lambertian part,
 *    for every out cell (symmetric Sinkhorn scaling). Because the scaled table stays
 *    symmetric, sum_o Omega_o w(o, c) = Omega_c (a(c) - k_d) as well: the light an in-cell receives
 * is reflected exactly by its albedo over the whole hemisphere. The first identity makes the white
 * furnace exact (a uniform incident radiance L gives I = a L in every direction), the second makes
 * the propagation conserve energy. LargestScaling() reports how far the factors are from 1, i.e.
 * how much the sampled BRDF missed its albedo.
 *
 * Access (the "suitable access data structure" of paper §5.2): for every pair of rows the
 * table keeps the second cumulative sum of w over the column difference, so the sum of w over
 * a strip of in-cells toward one out cell (StripWeight), and over a strip of in-cells toward
 * a strip of out cells (StripPairWeight), each costs O(1) whatever the strips' lengths.
 *
 * The whole hemisphere at once (Reflect): the exitant radiance toward every out cell from the
 * incident radiance of every in cell. By isotropy each pair of rows is a circular correlation
 * over the columns, I(ro, co) = sum_d w(ro, ri, d) e(ri, co + d); a row pair with at most
 * DirectTerms non-zero weights (the mirror's one or two cells) is summed directly, the others
 * as products of discrete Fourier transforms (Eigen's FFT): per band, one transform per lit in
 * row and one inverse per out row, and PhiBins/2 + 1 products per coupled row pair and band
 * (real ones: w is even in the column difference, as the models are in delta_phi, so its
 * transform is real; see the construction). That is O(ThetaBins^2 PhiBins) for a full table
 * instead of the O(D^2) of paper §5.2, D the cells (ThetaBins PhiBins): at most 0.2 million
 * products for the default 32 x 128 grid, against 50 million of the plain sum, and the
 * spectra take 1.6 MB (8 bytes per product). The transforms round at ~1e-16 of the
 * row's largest value, so values that should be 0 can come out as tiny negatives; they are set
 * to 0 (w >= 0 and e >= 0 make I >= 0).
 */
#ifndef SPHCOVER_REFLECTANCEWEIGHTS_H
#define SPHCOVER_REFLECTANCEWEIGHTS_H

#include <glm/vec3.hpp>

#include <complex>
#include <cstddef>
#include <vector>

namespace sphcover
{

class HemisphereGrid;
class Reflectance;

class ReflectanceWeights
{
public:
  /// Weights below this fraction of the table's largest are dropped (see the file comment).
  static constexpr double Cutoff = 1e-4;

  /// samples in [1, 8]: sub-directions per cell and axis (throws std::invalid_argument).
  ReflectanceWeights(const Reflectance& reflectance, const HemisphereGrid& grid, int samples = 2);

  int ThetaBins() const { return this->Rows; }
  int PhiBins() const { return this->Columns; }

  /// w(out cell (rowOut, c0), in cell (rowIn, c0 + deltaColumn)), deltaColumn in [0, PhiBins).
  glm::dvec3 Weight(int rowOut, int rowIn, int deltaColumn) const;
  /// sum over in-cells (rowIn, [begin, end)) of w(out cell (rowOut, columnOut), in-cell);
  /// 0 <= begin <= end <= PhiBins.
  glm::dvec3 StripWeight(int rowOut, int columnOut, int rowIn, int begin, int end) const;
  /// sum over out cells (rowOut, [outBegin, outEnd)) of StripWeight(rowOut, o, rowIn, begin, end).
  glm::dvec3 StripPairWeight(int rowOut, int outBegin, int outEnd, int rowIn, int begin, int end)
    const;
  /// sum over a whole row of in-cells, toward any out cell of rowOut.
  glm::dvec3 RowWeight(int rowOut, int rowIn) const;
  /// Row pairs with at most this many non-zero weights are summed directly by Reflect.
  static constexpr int DirectTerms = 4;
  /**
   * exitant[o] = sum_c w(o, c) incident[c] for every cell o of the grid (see the file
   * comment); both indexed row * PhiBins + column, `incident` of size ThetaBins * PhiBins,
   * rows that are all zero skipped. Thread-safe (the transforms' plans are local).
   */
  void Reflect(const std::vector<glm::dvec3>& incident, std::vector<glm::dvec3>& exitant) const;
  /// Reflect's working memory, kept by a caller that reflects often (one per thread).
  struct Scratch
  {
    std::vector<std::size_t> Lit;
    std::vector<double> Line;
    std::vector<std::complex<double>> In;
    std::vector<std::complex<double>> Sum;
  };
  void Reflect(const std::vector<glm::dvec3>& incident,
    std::vector<glm::dvec3>& exitant,
    Scratch& scratch) const;
  /// False when w vanishes between the two rows (the mirror's off-diagonal rows).
  bool RowsCoupled(int rowOut, int rowIn) const
  {
    return this->Coupled[static_cast<std::size_t>(rowOut * this->Rows + rowIn)] != 0;
  }
  /// The albedo (without k_d) every out cell of a row reproduces: sum_c w(o, c).
  const glm::dvec3& RowAlbedo(int row) const
  {
    return this->Albedos[static_cast<std::size_t>(row)];
  }
  /// max over rows and bands of |s - 1| of the normalization (0 for the mirror).
  double LargestScaling() const { return this->Scaling; }
  std::size_t MemoryBytes() const;
  /// The peak bytes of building a table for a thetaBins x phiBins grid (the weights, their
  /// cumulative sums and at most one spectrum per row pair), computed without allocating: it
  /// grows as ThetaBins^2 PhiBins (about 11 MB at 32 x 128, 5.6 GB at 256 x 1024).
  static std::size_t EstimateBytes(int thetaBins, int phiBins);

private:
  /// The steps of the constructor after the weights w are known (w indexed (rowOut * Rows +
  /// rowIn) * PhiBins + deltaColumn): the cumulative sums and Coupled, then Reflect's direct
  /// terms and spectra.
  void BuildCumulativeSums(const std::vector<glm::dvec3>& w);
  void BuildReflectForm(const std::vector<glm::dvec3>& w);
  const glm::dvec3* Cumulative(int rowOut, int rowIn) const
  {
    return this->Sums.data() + static_cast<std::size_t>(rowOut * this->Rows + rowIn) * this->Stride;
  }
  glm::dvec3 FirstSum(const glm::dvec3* c2, int t) const { return c2[t + 1] - c2[t]; }

  int Rows = 0;
  int Columns = 0;
  std::size_t Stride = 0;
  /// Per row pair: C2[t] = sum_{m < t} C1[m], C1[t] = sum_{m < t} w[m mod PhiBins], t in
  /// [0, 2 PhiBins + 1].
  std::vector<glm::dvec3> Sums;
  std::vector<char> Coupled;
  /// For Reflect, per row pair (rowOut * Rows + rowIn): its non-zero weights when they are at
  /// most DirectTerms (column difference, weight), DirectOffsets[pair] to DirectOffsets[pair +
  /// 1]; otherwise the index of its spectrum, the DFT of w over the column difference per band
  /// (real: w is even in the column difference), SpectrumLength values each, in Spectra (-1:
  /// summed directly or uncoupled).
  struct DirectTerm
  {
    int Delta;
    glm::dvec3 Weight;
  };
  std::vector<std::size_t> DirectOffsets;
  std::vector<DirectTerm> Directs;
  std::vector<int> SpectrumOf;
  std::vector<double> Spectra;
  int SpectrumLength = 0;
  /// Whether some out row needs the spectrum of this in row.
  std::vector<char> InRowSpectral;
  std::vector<glm::dvec3> Albedos;
  double Scaling = 0.0;
};

} // namespace sphcover

#endif
