// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file HemisphereGrid.h
 * @brief The hemisphere H_i over a characteristic point as a rectangular (theta, phi) grid of
 * cells (paper §3.3: "we have chosen to discretise the (theta, phi) rectangular domain of the
 * hemisphere into a rectangular grid of cells very much like a 2D pixel array"), its cosine
 * weighted cell measures, and the stratified sample directions by which the R-buffer fills
 * (paper §4.2.5) classify cells by coverage.
 *
 * Angles: theta in [0, pi/2] from the unit normal N, uniform in ThetaBins rows; phi in
 * [0, 2 pi) around N, uniform in PhiBins columns, measured from the tangent T (see
 * HemisphereFrame). Cell (row, column) spans [row, row+1) dtheta x [column, column+1) dphi;
 * its index is row * PhiBins + column.
 *
 * Measure: the projected solid angle (cosine-weighted) of a cell,
 *   integral cos(theta) sin(theta) dtheta dphi = dphi (cos 2 theta0 - cos 2 theta1) / 4,
 * (Documentation/Pipeline.md#spherical-cover), so that the cells sum to pi and sum_cells L cos dw
 * is the irradiance.
 *
 * Samples: each cell carries SamplesTheta x SamplesPhi sample directions on the midpoints of
 * strata of equal projected solid angle: uniform in s = sin^2(theta) (since
 * cos(theta) sin(theta) dtheta = ds / 2) and uniform in phi. Every sample therefore stands for
 * the same share CellMeasure(row) / SamplesPerCell() of its cell, and the fraction of a
 * cell's samples that a source covers estimates the cosine-weighted fraction of the cell it
 * covers (midpoint rule in (s, phi)). The sample rows and columns form a fine grid of
 * ThetaBins*SamplesTheta x PhiBins*SamplesPhi directions; sample (sampleRow, sampleColumn)
 * lies in cell (sampleRow / SamplesTheta, sampleColumn / SamplesPhi).
 */
#ifndef SPHCOVER_HEMISPHEREGRID_H
#define SPHCOVER_HEMISPHEREGRID_H

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sphcover
{

class BezierPatch;
struct Patch;

/**
 * @brief The local frame of a hemisphere: origin P_i, unit normal N (theta = 0), unit tangent
 * T (phi = 0) and B = N x T (phi = pi/2), a right-handed frame (T, B, N).
 *
 * T is dP/du at the characteristic point projected onto the tangent plane and normalised
 * (Documentation/Pipeline.md#spherical-cover). Where that projection vanishes (dP/du = 0 at a
 * collapsed edge; a characteristic point at a parametric centre of a regular patch never has it) T
 * is dP/dv x N normalised, which is the direction dP/du would have; where that vanishes too, T is
 * the world axis (x, then y, then z) least parallel to N, projected onto the tangent plane: a fixed
 * tangent.
 */
struct HemisphereFrame
{
  glm::dvec3 Origin{ 0.0 };
  glm::dvec3 Normal{ 0.0, 0.0, 1.0 };
  glm::dvec3 Tangent{ 1.0, 0.0, 0.0 };
  glm::dvec3 Bitangent{ 0.0, 1.0, 0.0 };

  /// The frame at `origin` with unit `normal`, phi measured from `partialU` projected (with
  /// the fallbacks above, `partialV` first).
  static HemisphereFrame FromPartials(const glm::dvec3& origin,
    const glm::dvec3& normal,
    const glm::dvec3& partialU,
    const glm::dvec3& partialV);
  /// The frame of a patch's characteristic point (its Point and Normal, the partials of its
  /// Geometry at the parametric centre).
  static HemisphereFrame OfPatch(const Patch& patch);

  /// World direction -> local coordinates (components along T, B, N).
  glm::dvec3 ToLocal(const glm::dvec3& world) const;
  /// Local coordinates -> world direction.
  glm::dvec3 ToWorld(const glm::dvec3& local) const;
};

class HemisphereGrid
{
public:
  /**
   * thetaBins, phiBins in [1, 65535] (strips store rows and columns as uint16), at most
   * 2^31 - 1 cells (cells are indexed by int); samplesTheta, samplesPhi in [1, 16]. Throws
   * std::invalid_argument otherwise.
   */
  HemisphereGrid(int thetaBins, int phiBins, int samplesTheta = 3, int samplesPhi = 3);
  /// The constructor's checks alone (nothing allocated): throws std::invalid_argument.
  static void CheckSizes(int thetaBins, int phiBins, int samplesTheta, int samplesPhi);

  int ThetaBins() const { return this->ThetaBinCount; }
  int PhiBins() const { return this->PhiBinCount; }
  int CellCount() const { return this->ThetaBinCount * this->PhiBinCount; }
  double ThetaStep() const { return this->DeltaTheta; }
  double PhiStep() const { return this->DeltaPhi; }

  int CellIndex(int row, int column) const { return row * this->PhiBinCount + column; }
  int RowOfCell(int cell) const { return cell / this->PhiBinCount; }
  int ColumnOfCell(int cell) const { return cell % this->PhiBinCount; }

  /// theta at the lower edge of a row (row = ThetaBins() gives pi/2).
  double RowTheta(int row) const;
  /// Projected solid angle of every cell of a row: dphi (cos 2 theta0 - cos 2 theta1) / 4.
  double CellMeasure(int row) const { return this->RowMeasures[static_cast<size_t>(row)]; }
  double CellMeasureOfCell(int cell) const { return this->CellMeasure(this->RowOfCell(cell)); }
  /// Sum of all cell measures (pi up to rounding).
  double TotalMeasure() const;

  /// Local unit direction (sin t cos p, sin t sin p, cos t).
  static glm::dvec3 LocalDirection(double theta, double phi);
  /// Angles of a local direction (need not be unit): theta in [0, pi], phi in [0, 2 pi).
  static void LocalAngles(const glm::dvec3& local, double& theta, double& phi);
  /// The cell containing (theta, phi); -1 when theta is outside [0, pi/2] (below the tangent
  /// plane) or not finite. phi is taken modulo 2 pi. theta = pi/2 exactly belongs to the last
  /// row.
  int CellOfAngles(double theta, double phi) const;
  /// The cell containing a local direction; -1 below the tangent plane. The same cell as
  /// CellOfAngles(LocalAngles(local)) for every direction, without trigonometry for all but
  /// those within 1e-9 rad of a cell's edge: the row and column are found by the signs of cross
  /// products with the edges' (sin, cos) (binary searches over ThetaBins() + 1 and PhiBins() + 1
  /// edges), and a direction that close to an edge takes the atan2 path, whose rounding alone
  /// decides there.
  int CellOfLocalDirection(const glm::dvec3& local) const;
  /// The unit local direction at the centre (in theta and phi) of a cell.
  glm::dvec3 CellCentreDirection(int cell) const;

  // --- samples -------------------------------------------------------------------------------
  int SamplesTheta() const { return this->SamplesThetaCount; }
  int SamplesPhi() const { return this->SamplesPhiCount; }
  int SamplesPerCell() const { return this->SamplesThetaCount * this->SamplesPhiCount; }
  int SampleRows() const { return this->ThetaBinCount * this->SamplesThetaCount; }
  int SampleColumns() const { return this->PhiBinCount * this->SamplesPhiCount; }
  std::size_t SampleCount() const
  {
    return static_cast<std::size_t>(this->SampleRows()) *
      static_cast<std::size_t>(this->SampleColumns());
  }
  /// Index of sample (sampleRow, sampleColumn) in row-major order of the fine sample grid.
  std::size_t SampleIndex(int sampleRow, int sampleColumn) const
  {
    return static_cast<std::size_t>(sampleRow) * static_cast<std::size_t>(this->SampleColumns()) +
      static_cast<std::size_t>(sampleColumn);
  }
  /// cos(theta) and sin(theta) of a sample row (the midpoint of its stratum in sin^2 theta).
  double SampleCosTheta(int sampleRow) const
  {
    return this->SampleCos[static_cast<size_t>(sampleRow)];
  }
  double SampleSinTheta(int sampleRow) const
  {
    return this->SampleSin[static_cast<size_t>(sampleRow)];
  }
  /// phi of a sample column: (sampleColumn + 1/2) dphi / SamplesPhi.
  double SamplePhi(int sampleColumn) const
  {
    return (sampleColumn + 0.5) * this->DeltaPhi / this->SamplesPhiCount;
  }
  /// Unit local direction of a sample.
  glm::dvec3 SampleDirection(int sampleRow, int sampleColumn) const;
  /// The sample columns whose phi lies in [phiBegin, phiEnd) (phi in [0, 2 pi], phiBegin <=
  /// phiEnd) as [first, last); first == last when none.
  void SampleColumnsIn(double phiBegin, double phiEnd, int& first, int& last) const;

  /**
   * The samples of a cell ordered by distance from the cell's centre in the cell's own
   * normalised (s, phi) coordinates, nearer first, ties by index: entries are a * SamplesPhi()
   * + b for the sample (a, b) of the cell. The R-buffers break ties between sources with it
   * (the tied source met first in this order wins), which needs no depth and treats both sides
   * of a boundary alike.
   */
  const std::vector<int>& SamplesFromCentre() const { return this->CentreOrder; }

private:
  int ThetaBinCount;
  int PhiBinCount;
  int SamplesThetaCount;
  int SamplesPhiCount;
  double DeltaTheta;
  double DeltaPhi;
  std::vector<double> RowMeasures;
  std::vector<double> SampleCos;
  std::vector<double> SampleSin;
  std::vector<double> ColumnCos;
  std::vector<double> ColumnSin;
  /// cos and sin of the row edges r DeltaTheta (r = 0 .. ThetaBins) and of the column edges
  /// c DeltaPhi (c = 0 .. PhiBins): CellOfLocalDirection's tests.
  std::vector<double> RowEdgeCos;
  std::vector<double> RowEdgeSin;
  std::vector<double> ColumnEdgeCos;
  std::vector<double> ColumnEdgeSin;
  std::vector<int> CentreOrder;
};

} // namespace sphcover

#endif
