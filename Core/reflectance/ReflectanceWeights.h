// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file ReflectanceWeights.h
 * @brief The precomputed weight tables w(out, in-cell) of paper §3.5 ("For A Surface With
 * General Reflectance: I(theta_r, phi_r) = sum_ij w_ij e_ij ... w_ij is precomputed and set up
 * in tables depending on surface properties") over the cells of a HemisphereGrid.
 *
 * The exitant radiance toward out cell o from incident radiance e_c per in-cell c is
 *     I(o) = k_d / pi sum_c Omega_c e_c + sum_c w(o, c) e_c,   w(o, c) ~ (f(c, o) - k_d / pi)
 * Omega_c: the table holds the BRDF without its Lambertian part k_d, which the propagation shoots
 * in closed form (paper §5.2). By isotropy w depends on the two cells' rows and their column
 * difference only: ThetaBins^2 x PhiBins values per band.
 *
 * Construction, the constructor's steps: an ideal mirror puts k_s on the mirror cell (§3.5.1);
 * another BRDF is averaged over Samples x Samples sub-directions of both cells, made symmetric
 * (discrete reciprocity) and even in the column difference, cleared below Cutoff times its
 * largest value (§5.2 (ii)) and scaled per row and band (symmetric Sinkhorn scaling) so that
 * sum_c w(o, c) = a(o) - k_d, the directional albedo without k_d, for every out cell; the scaled
 * table stays symmetric, so an in-cell's light is reflected exactly by its albedo as well.
 * LargestScaling() reports how far the factors are from 1.
 *
 * Access (§5.2's "suitable access data structure"): per row pair the second cumulative sum of w
 * over the column difference, so StripWeight and StripPairWeight cost O(1) whatever the strips'
 * lengths. Reflect serves the whole hemisphere at once: per row pair a circular correlation over
 * the columns, summed directly with at most DirectTerms weights and by FFT otherwise,
 * O(ThetaBins^2 PhiBins) rather than §5.2's O(D^2); the results are clamped at 0.
 *
 * Construction costs O(ThetaBins^2 PhiBins Samples^4) BRDF evaluations; memory: EstimateBytes.
 * The derivations and sizes: Documentation/notes/reflectance.md.
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
