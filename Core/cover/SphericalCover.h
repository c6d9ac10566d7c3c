// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SphericalCover.h
 * @brief The spherical cover of paper §3.3: for every characteristic point P_i its tessellated
 * hemisphere H_i = union_j h_ij, where h_ij is the region of H_i through which P_i sees patch
 * Q_j, stored as the sparse N x N matrix whose row i is H_i and whose column j lists the
 * hemispheres Q_j appears in ("Each row represents a hemisphere ... Each column j gives all
 * the spherical covers to which the j-th characteristic point contributes").
 *
 * Each H_i is the R-buffer of P_i (RBuffer, filled by projection or by ray casting, paper
 * §4.2.5 / §4.3 Step 2), turned into strips (§3.3: "we store the subregion as a sequence of
 * strips ranging from phi_1 to phi_2 in a row of the (theta, phi) cell array"); §4.3 Step 4:
 * "Extract h_ij for each j as a collection of strips from the R buffer".
 *
 * Storage (compressed sparse rows, one allocation per array; bytes per item):
 *  - Strip: uint16 theta row, uint16 phi begin, uint16 phi end (exclusive): 6 bytes, plus its
 *    mean R as a float in a parallel array: 10 bytes per strip. A strip never wraps across the
 *    phi seam (a run through phi = 0 is two strips). Strips of one h_ij are consecutive, by
 *    row then phi.
 *  - Entry (a non-null H(i, j)): uint32 source j, uint32 index of its first strip (its strips
 *    run to the next entry's first strip): 8 bytes; plus a float unoccluded projected solid
 *    angle (below) and the column index (uint32 receiver, uint32 entry): 20 bytes per entry. A
 *    row's entries are sorted by source.
 *  - Per patch: row offset, column offset (uint64 each) and area (double): 24 bytes.
 * The source index is stored once per h_ij, not per strip.
 *
 * For paper §4.3 Steps 3 and 5 (done by CoverRefinement, not here) each entry carries the
 * cells h_ij keeps (VisibleCells, ProjectedSolidAngle) and, with the projection fill, the
 * projected solid angle of Q_j's unoccluded projection (UnoccludedProjectedSolidAngle, at
 * sample resolution): their ratio tells how much of Q_j is hidden (up to the rounding of
 * boundary cells), the strips whether h_ij is connected. The strips' row-major order is the
 * one the row-by-row interpolation of §3.4 walks.
 *
 * Measured regions. A region's measure (ProjectedSolidAngle) is the sum of its cells' measures,
 * except in the rows that see a source of SphericalCoverOptions::MeasuredSurfaces with the ray
 * fill: there each such region h_ij gets the projected solid angle of the visible part of Q_j
 * integrated over Q_j (RayCastFiller::VisibleProjectedSolidAngle), and the row's other regions
 * are scaled by one factor so that the row keeps its covered measure (a closed scene's rows
 * still sum to pi, the white furnace stays exact); the cells keep their sources. A source that
 * wins no cell of a row stays unseen there. Measures are stored per entry (a float) only when
 * some row has one (why, measured: Documentation/notes/time-to-accuracy.md).
 *
 * Panes (paper §5.4; SphericalCoverOptions::SurfaceTransmittance). A thin pane passes light
 * straight through, so along a direction P_i receives L(y_1) + T_1 L(y_2) + T_1 T_2 L(y_3) + ...,
 * y_1, y_2, ... the surfaces the line meets in order, L a surface's own emitted and reflected
 * radiance, T_k the transmittance of the pane y_k. Row i then has, besides its regions of layer 0
 * (what P_i sees first: they partition the covered hemisphere as without panes), regions of layer
 * k >= 1: the cells in which the first k surfaces met are panes, by what the (k+1)-th is
 * (RayCastFiller::FillBehindPanes). Each such entry carries its filter, the product of the
 * transmittances of the k panes in front of its source (per band; in each cell those of the cells'
 * winners of the layers before), and entries of one source with different layers or filters are
 * different entries; they overlap the pane's region of the layer before. A pane receives what
 * reaches its side (its own entries) and passes on what it lets through by the filtered entries of
 * the points behind it: nothing is counted twice, the filtered entries are reciprocal and a white
 * furnace with panes stays exact (why: Documentation/notes/panes-and-textures.md, 2026-12-04). At
 * most MaxPaneDepth layers behind the first (light through more panes is dropped). FindEntry,
 * ExpandRow, CoveredProjectedSolidAngle and FormFactors are of layer 0 (the geometric cover, panes
 * opaque); the propagation walks every entry. Ray fill only.
 * Complexity: one R-buffer fill per receiver (Build) over the candidates CandidateCulling
 * keeps (O(N^2) pairs at worst, the paper's O(N^2) cover); memory O(entries + strips).
 */
#ifndef SPHCOVER_SPHERICALCOVER_H
#define SPHCOVER_SPHERICALCOVER_H

#include "cover/CandidateCulling.h"
#include "cover/HemisphereGrid.h"
#include "cover/HemisphereInterpolation.h"
#include "cover/RBuffer.h"
#include "math/ParallelFor.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sphcover
{

struct Patch;
class RayCastFiller;
class RayCaster;

struct SphericalCoverOptions
{
  int ThetaBins = 32;
  int PhiBins = 128;
  /// Samples per cell along theta and phi for the coverage classification.
  int SamplesTheta = 3;
  int SamplesPhi = 3;
  RBufferFill Fill = RBufferFill::Projection;
  RBufferFillOptions FillOptions;
  /// Receivers per ParallelFor call; progress and abort are checked between calls. 0: 64.
  std::size_t BatchSize = 0;
  /**
   * Surfaces (by Patch::SurfaceIndex; empty: none) whose regions are measured on the source
   * rather than in cells (ray fill only; see "Measured regions" in the file comment): the
   * scene's lamps (BrightEmitters.h), whose direct light the cells' vote measures to about 10 %
   * per point.
   */
  std::vector<bool> MeasuredSurfaces;
  /**
   * Per surface (Patch::SurfaceIndex; empty or shorter: opaque) the transmittance of a thin pane
   * (Material::Transmittance; all zero: opaque): see "Panes" in the file comment. Sets the
   * fill's PaneSurfaces. Needs the ray fill (Build throws std::invalid_argument otherwise).
   */
  std::vector<glm::vec3> SurfaceTransmittance;
  /// Most panes a region is seen through (the layers after the first); 0: panes are opaque.
  int MaxPaneDepth = 4;
  /// Hemispheres interpolated from their neighbours' instead of computed (paper §3.4, §4.3
  /// note 5; ray fill with AdaptiveSampling only): HemisphereInterpolation.h.
  HemisphereInterpolationOptions Interpolation;
};

/**
 * What the layers behind panes leave out (see "Panes" in SphericalCover's file comment): the
 * cells, over all rows, whose last kept layer (MaxPaneDepth behind the first) still shows a
 * pane, so that the light from behind that pane is dropped, and their projected solid angle
 * weighted by the transmittance through all of those panes (the mean of the bands), summed over
 * the rows: over pi times the rows it is the fraction of the hemispheres' light lost at most.
 */
struct PaneLimitDrops
{
  uint64_t Cells = 0;
  double ProjectedSolidAngle = 0.0;

  PaneLimitDrops& operator+=(const PaneLimitDrops& other)
  {
    this->Cells += other.Cells;
    this->ProjectedSolidAngle += other.ProjectedSolidAngle;
    return *this;
  }
};

/**
 * The order of a row's entries (see "Panes"): by source, then layer, then filter band by band;
 * -1, 0 or 1. A column lists each receiver's entries in this order too, which is what lets the
 * propagation match an entry with its transposed one in one merge.
 */
int CompareEntryKeys(uint32_t sourceA,
  unsigned layerA,
  const glm::vec3& filterA,
  uint32_t sourceB,
  unsigned layerB,
  const glm::vec3& filterB);

class SphericalCover
{
public:
  /// One run of cells of a theta row held by one source: columns [PhiBegin, PhiEnd).
  struct Strip
  {
    uint16_t Row;
    uint16_t PhiBegin;
    uint16_t PhiEnd;
  };
  /// A non-null element H(i, j) of the matrix.
  struct Entry
  {
    uint32_t Source;
    uint32_t FirstStrip;
  };
  /// An element of column j: the receiver i whose hemisphere holds Q_j, and the entry.
  struct ColumnEntry
  {
    uint32_t Receiver;
    uint32_t EntryIndex;
  };

  SphericalCover();
  ~SphericalCover();
  SphericalCover(SphericalCover&&) noexcept;
  SphericalCover& operator=(SphericalCover&&) noexcept;

  /**
   * Builds the cover of the patches (every patch is both a receiver and a source). Returns
   * false, leaving the cover empty, when `progress` returned false. The ray fill casts against
   * `rays` when given (a RayCaster of these patches with RayCastOptions(options.FillOptions),
   * shared with the direct light: RayCastFiller), else builds its own. Throws
   * std::invalid_argument for bad options or more than 2^32 - 1 patches, std::runtime_error if
   * the ray fill cannot initialise Embree. The receivers run through `parallelFor` in batches;
   * progress is reported, and abort honoured, from the calling thread between batches. Rows
   * are computed independently and appended in receiver order, so the cover does not depend on
   * the thread count.
   */
  bool Build(const std::vector<Patch>& patches,
    const SphericalCoverOptions& options = {},
    const ParallelFor& parallelFor = SequentialFor,
    const ProgressCallback& progress = nullptr,
    std::shared_ptr<const RayCaster> rays = nullptr);

  bool Empty() const { return this->RowOffsets.size() < 2; }
  std::size_t PatchCount() const
  {
    return this->RowOffsets.empty() ? 0 : this->RowOffsets.size() - 1;
  }
  std::size_t EntryCount() const { return this->Entries.size(); }
  std::size_t StripCount() const { return this->Strips.size(); }
  const SphericalCoverOptions& Options() const { return this->BuildOptions; }
  /// The grid of every hemisphere (valid after Build).
  const HemisphereGrid& Grid() const { return *this->GridPointer; }

  // --- rows (hemispheres) ----------------------------------------------------------------------
  /// Entries [EntryBegin(i), EntryEnd(i)) form row i, sorted by source.
  std::size_t EntryBegin(std::size_t receiver) const { return this->RowOffsets[receiver]; }
  std::size_t EntryEnd(std::size_t receiver) const { return this->RowOffsets[receiver + 1]; }
  const Entry& EntryAt(std::size_t entry) const { return this->Entries[entry]; }
  // --- panes (see "Panes" in the file comment) ------------------------------------------------
  /// Whether some entry is seen through a pane (the cover of a scene with panes).
  bool HasPanes() const { return !this->Layers.empty(); }
  /// How many panes lie in front of entry e's source (0: seen directly).
  unsigned Layer(std::size_t entry) const { return this->Layers.empty() ? 0 : this->Layers[entry]; }
  /// The product of the transmittances of those panes, per band (1 for layer 0).
  glm::dvec3 Filter(std::size_t entry) const;
  /// The transmittance of patch j's pane (0: opaque).
  glm::dvec3 PaneTransmittance(std::size_t patch) const;

  /// The entry H(i, j) of layer 0, or -1 when h_ij is null.
  std::ptrdiff_t FindEntry(std::size_t receiver, std::size_t source) const;
  /// Strips [StripBegin(e), StripEnd(e)) of entry e.
  std::size_t StripBegin(std::size_t entry) const { return this->Entries[entry].FirstStrip; }
  std::size_t StripEnd(std::size_t entry) const;
  const Strip& StripAt(std::size_t strip) const { return this->Strips[strip]; }
  /// Mean distance R over the strip's cells.
  float StripDepth(std::size_t strip) const { return this->StripDepths[strip]; }
  /// Cells of h_ij.
  uint32_t VisibleCells(std::size_t entry) const;
  /// Projected solid angle of the unoccluded projection of Q_j in H_i (see the file comment);
  /// 0 when !HasUnoccluded().
  float UnoccludedProjectedSolidAngle(std::size_t entry) const { return this->Unoccluded[entry]; }
  bool HasUnoccluded() const { return this->UnoccludedKnown; }
  /// The source of every cell of H_i (RBuffer::NoSource where none), index row*PhiBins+column.
  std::vector<int32_t> ExpandRow(std::size_t receiver) const;

  // --- columns ---------------------------------------------------------------------------------
  /// Column j: [ColumnBegin(j), ColumnEnd(j)) index ColumnAt, receivers ascending.
  std::size_t ColumnBegin(std::size_t source) const { return this->ColumnOffsets[source]; }
  std::size_t ColumnEnd(std::size_t source) const { return this->ColumnOffsets[source + 1]; }
  const ColumnEntry& ColumnAt(std::size_t k) const { return this->Columns[k]; }

  // --- measures --------------------------------------------------------------------------------
  /// Projected solid angle of h_ij for entry e: the sum of its cells' measures.
  double ProjectedSolidAngle(std::size_t entry) const;
  /// Projected solid angle of h_ij (0 when null).
  double ProjectedSolidAngle(std::size_t receiver, std::size_t source) const;
  /// Sum over the covered cells of H_i (pi inside a closed scene).
  double CoveredProjectedSolidAngle(std::size_t receiver) const;
  /// Number of non-null h_ij in row i.
  std::size_t VisibleSourceCount(std::size_t receiver) const
  {
    return this->EntryEnd(receiver) - this->EntryBegin(receiver);
  }
  double PatchArea(std::size_t patch) const { return this->Areas[patch]; }
  /**
   * Area-weighted form factors between groups of patches (e.g. surfaces):
   * F_ab = (1 / A_a) sum_{i in a} A_i sum_{j in b} Omega(h_ij) / pi, A_a = sum_{i in a} A_i.
   * groupOfPatch[i] in [0, groupCount) (or negative: patch ignored as a receiver and a
   * source). Returns the groupCount x groupCount matrix, row-major (row a: from group a).
   */
  std::vector<double> FormFactors(const std::vector<int>& groupOfPatch, int groupCount) const;
  /// One group's part of a row's form factors (FormFactorSums).
  struct GroupSum
  {
    int32_t Group = 0;
    double Sum = 0.0;
  };
  /**
   * What each row adds to FormFactors: per receiver i whose group is >= 0, the sum over its
   * layer-0 entries of the sources of each group b of Omega(h_ij) / pi (in entry order), one
   * GroupSum per group seen, ordered by group; empty for the other receivers and empty rows
   * (a share's other rows). A share's sums are the whole cover's for its rows, so the sums of
   * the ranks' shares, put in receiver order, give FormFactorsOf the whole cover's
   * FormFactors bit for bit. Throws std::invalid_argument as FormFactors.
   */
  std::vector<std::vector<GroupSum>> FormFactorSums(const std::vector<int>& groupOfPatch,
    int groupCount) const;
  /**
   * The form factors of FormFactors from every receiver's sums (`rowSums`, one per patch, as
   * FormFactorSums gives them) and area (`areas`): summed in receiver order, as FormFactors
   * does. Throws std::invalid_argument for sizes that differ from groupOfPatch's or a group
   * out of range.
   */
  static std::vector<double> FormFactorsOf(const std::vector<std::vector<GroupSum>>& rowSums,
    const std::vector<int>& groupOfPatch,
    int groupCount,
    const std::vector<double>& areas);

  // --- storage ---------------------------------------------------------------------------------
  /// The cover's own arrays, for saving and loading it (the columns are derived from the rows).
  struct Arrays
  {
    int ThetaBins = 0;
    int PhiBins = 0;
    int SamplesTheta = 0;
    int SamplesPhi = 0;
    int Fill = 0;
    std::vector<uint64_t> RowOffsets;
    std::vector<Entry> Entries;
    std::vector<float> Unoccluded;
    bool UnoccludedKnown = false;
    std::vector<Strip> Strips;
    std::vector<float> StripDepths;
    std::vector<double> Areas;
    /// Per entry the measure of its region, or empty: the cells' (see the file comment).
    std::vector<float> Measures;
    /// Panes (empty without): per entry its layer, and its filter (3 floats per entry); per
    /// patch its transmittance (3 floats per patch).
    std::vector<uint8_t> Layers;
    std::vector<float> Filters;
    std::vector<float> Transmittances;
  };
  Arrays ExportArrays() const&;
  /// The arrays moved out, the cover left empty: for a caller done with the cover that stores
  /// its arrays elsewhere (vtkSphericalCoverArrays::Store), without a second copy.
  Arrays ExportArrays() &&;
  /// Replaces the cover with saved arrays after checking that they are consistent (offsets,
  /// indices and cell ranges); returns an explanation (and leaves the cover empty) if not.
  std::string ImportArrays(Arrays arrays);

  /// Whether the entries carry measures of their own (some row measured: see the file comment).
  bool HasMeasures() const { return !this->Measures.empty(); }

  // --- statistics and memory -------------------------------------------------------------------
  /// Candidate culling counts summed over all receivers (projection fill only).
  const CullingStatistics& Culling() const { return this->CullingCounts; }
  /// The cells behind more panes than MaxPaneDepth, summed over the rows in receiver order (a
  /// build's figure: a cover loaded from saved arrays has none).
  const PaneLimitDrops& PaneLimit() const { return this->PaneLimitCounts; }
  /// Bytes held by the cover's arrays.
  std::size_t MemoryBytes() const;
  /// Bytes per strip, per entry and per patch (see the file comment).
  static constexpr std::size_t BytesPerStrip = sizeof(Strip) + sizeof(float);
  static constexpr std::size_t BytesPerEntry = sizeof(Entry) + sizeof(float) + sizeof(ColumnEntry);
  static constexpr std::size_t BytesPerPatch = 2 * sizeof(uint64_t) + sizeof(double);
  /**
   * An upper bound of MemoryBytes() for n patches, known before building: every cell a strip
   * of its own and an entry of its own (at most min(n, cells) entries per row).
   */
  static std::size_t UpperBoundBytes(std::size_t patches, const SphericalCoverOptions& options);
  /// The rows EstimateBytes builds unless told otherwise.
  static constexpr std::size_t EstimateSamples = 16;
  /**
   * An estimate of MemoryBytes() from a few rows actually built (sampleReceivers of them,
   * spread evenly over the patches, with their layers behind panes and, when some surface is
   * measured, a measure per entry) scaled to all n rows; costs sampleReceivers / n of a build,
   * and the ray fill's caster unless `rays` is given (as Build). With every row sampled and
   * without interpolated hemispheres, MemoryBytes() of the build itself or more (every entry
   * counted measured when some surface is).
   */
  static std::size_t EstimateBytes(const std::vector<Patch>& patches,
    const SphericalCoverOptions& options,
    std::size_t sampleReceivers = EstimateSamples,
    std::shared_ptr<const RayCaster> rays = nullptr);
  /// Working memory of one building thread (its R-buffer and fill scratch), in bytes.
  static std::size_t WorkingBytesPerThread(const SphericalCoverOptions& options);
  /// Working memory of a build on `threads` threads: their R-buffers and scratch at once, and
  /// the grid's tables. From the options alone: nothing is allocated.
  static std::size_t WorkingBytes(const SphericalCoverOptions& options, std::size_t threads);
  /**
   * Why building the cover of `patches` on `threads` threads would not fit in `limitBytes`, or
   * "". The working memory is checked first, from the options alone (a grid too fine for the
   * limit is refused without allocating anything); only when it fits are a few rows built for
   * EstimateBytes (none for an empty `patches`: the check of the grid alone, which a caller can
   * make before the subdivision), with `rays` as Build. Throws std::invalid_argument for a grid
   * HemisphereGrid rejects.
   */
  static std::string MemoryProblem(const std::vector<Patch>& patches,
    const SphericalCoverOptions& options,
    std::size_t threads,
    std::size_t limitBytes,
    std::shared_ptr<const RayCaster> rays = nullptr);

private:
  // Rows are independent (paper §4.3: one R-buffer per characteristic point): a distributed
  // solve builds, cuts and joins them in shares (distributed/RowShares.h) with BuildRows,
  // EmptyArrays, CheckArrays and Adopt.
  friend class RowShares;
  struct Row;
  /// Build's rows of `receivers` (ascending), one after the other from row 0, with their areas
  /// (all receivers: the whole cover, without its columns); false, with the cover cleared,
  /// when aborted.
  bool BuildRows(const std::vector<Patch>& patches,
    const SphericalCoverOptions& options,
    const std::vector<std::size_t>& receivers,
    const ParallelFor& parallelFor,
    const ProgressCallback& progress,
    std::shared_ptr<const RayCaster> rays);
  /// Why `arrays` are not a consistent cover ("" when they are).
  static std::string CheckArrays(const Arrays& arrays);
  /// Arrays on the grid and with the fill of `options`, without rows (RowOffsets {0}).
  static Arrays EmptyArrays(const SphericalCoverOptions& options, bool unoccludedKnown);
  /// Takes consistent `arrays` with `options` as the build's and derives the columns.
  void Adopt(Arrays arrays, const SphericalCoverOptions& options);
  /// ExportArrays' one body: the arrays of `cover` copied (a const cover) or moved (an rvalue).
  template<typename Cover>
  static Arrays ArraysOf(Cover&& cover);
  /// Appends the regions of `buffer` to `row` as entries of layer `layer`; `filterOfCell` (by
  /// cell index) gives their filters when layer > 0.
  static void ExtractRow(const RBuffer& buffer,
    Row& row,
    unsigned layer = 0,
    const std::vector<glm::vec3>* filterOfCell = nullptr);
  /// Per patch its pane's transmittance from options.SurfaceTransmittance (empty: no panes, or
  /// MaxPaneDepth 0), and the fill's PaneSurfaces set in `fill` to match; throws
  /// std::invalid_argument for panes without the ray fill.
  static std::vector<glm::vec3> PaneTransmittances(const std::vector<Patch>& patches,
    const SphericalCoverOptions& options,
    RBufferFillOptions& fill);
  /// Adds at most `maxDepth` layers behind panes to the row of `front`'s receiver (see
  /// "Panes"), then sorts its entries by (source, layer, filter); what lies behind more panes
  /// is counted in the row's PaneLimit.
  static void ExtractLayersBehindPanes(const RayCastFiller& filler,
    const std::vector<glm::vec3>& transmittanceOfPatch,
    int maxDepth,
    RBuffer& front,
    RBuffer& behind,
    Row& row);
  /// Measures the row's regions of measured surfaces on their sources (see the file comment);
  /// piecesOfSurface[s] lists the patches of measured surface s, ascending.
  void MeasureRow(std::size_t receiver,
    const RayCastFiller& filler,
    const std::vector<Patch>& patches,
    const std::vector<std::vector<uint32_t>>& piecesOfSurface,
    Row& row) const;
  void AppendRow(Row& row);
  /// The layer-0 cells of a row (a row being built, or row `row` of this cover) painted with
  /// their sources and their strips' R; cells of no entry are left as they are.
  static void PaintRowCells(const HemisphereGrid& grid,
    const Row& row,
    int32_t* cellSources,
    float* cellDepths);
  void PaintCoverRowCells(std::size_t row, int32_t* cellSources, float* cellDepths) const;
  /// The sum of the cells' measures of the strips [first, last).
  static double MeasureOfStrips(const HemisphereGrid& grid, const Strip* first, const Strip* last);
  /// The sum of the measures of entry e's cells.
  double CellsMeasure(std::size_t entry) const;
  /// Derives the columns (which rows contain each source) from the rows.
  void BuildColumns();
  void Clear();

  SphericalCoverOptions BuildOptions;
  std::unique_ptr<HemisphereGrid> GridPointer;
  std::vector<uint64_t> RowOffsets;
  std::vector<Entry> Entries;
  std::vector<float> Unoccluded;
  std::vector<Strip> Strips;
  std::vector<float> StripDepths;
  std::vector<uint64_t> ColumnOffsets;
  std::vector<ColumnEntry> Columns;
  std::vector<double> Areas;
  std::vector<float> Measures;
  std::vector<uint8_t> Layers;
  std::vector<float> Filters;
  std::vector<float> Transmittances;
  bool UnoccludedKnown = false;
  CullingStatistics CullingCounts;
  PaneLimitDrops PaneLimitCounts;
};

} // namespace sphcover

#endif
