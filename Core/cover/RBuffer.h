// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RBuffer.h
 * @brief The R-buffer of paper §4.2.5 / §4.3 Step 2: for every (theta, phi) cell of the
 * hemisphere H_i of a characteristic point P_i, the nearest source patch Q_j seen through it
 * (or none) and its distance R, "a Z-buffer like algorithm ... in which the distance R in
 * spherical coordinates is used in place of Z".
 *
 * Two levels:
 *  - samples: the fine grid of HemisphereGrid sample directions (SamplesTheta x SamplesPhi per
 *    cell). A fill (RBufferFiller: projection or ray casting) writes, per sample, the nearest
 *    front-facing source along the sample ray and, where it knows it, the exact distance R and
 *    whether the ray meets that surface at a grazing angle. With the ray fill's
 *    AdaptiveSampling the samples of a uniform cell (its centre and its 8 neighbours' centres
 *    show one surface, or nothing) are copies of its centre sample, not rays of their own
 *    (RayCastFill.h): the samples then estimate coverage at sample resolution only in the
 *    cells next to a change of surface, and at cell-centre resolution elsewhere;
 *  - cells: Classify() gives every cell by coverage, in two rounds of plurality votes over its
 *    samples: first the group (the surface of the source patch; uncovered samples are a group
 *    of their own), then one patch of the winning group. With DiffuseRounding the vote carries
 *    its rounding error along the theta row (every group and patch carries the samples it
 *    covered minus perCell for every cell it won, the largest count + carry among the
 *    candidates present in the cell wins, "no source" carries nothing, the carries restart at
 *    each row), so a source's cells in a row sum to its covered samples. A tie goes to the
 *    candidate met first in HemisphereGrid::SamplesFromCentre() order; the cell's R is the
 *    winner's distance along its first sample in that order. Why two rounds and the carry,
 *    with measurements: Documentation/notes/r-buffer-vote.md.
 *
 * Visibility, shared by both fills: surfaces are opaque and one-sided (Data/scenes/FORMAT.md).
 * A sample is covered by Q_j if the first surface the ray P_i + t w, t > 0, meets is Q_j and
 * it meets its front side. A back side met first hides what lies behind it but sends no light
 * (BackFacesOcclude, the default); BackFacesOcclude = false is paper §4.2.1's dropping of
 * back-facing patches (back sides transparent): the same in a closed, consistently oriented
 * scene, but it breaks reciprocity A_i F_ij = A_j F_ji where points see back sides (the floor
 * under the Cornell box's bottomless blocks, the teapot's open lid gap). A concave receiver
 * patch (the inside of a sphere) meets rays of its own hemisphere near the horizon:
 * CountSelfVisibility records them as h_ii (needed for energy conservation and for the covered
 * projected solid angle to be pi in a curved closed scene) or leaves them empty (paper §3.3:
 * "a patch is not visible to itself"). Hits closer than SelfExclusionFraction * Size() of the
 * receiver patch are P_i itself, never its own patch.
 *
 * Complexity: Classify() is O(samples x distinct sources per cell); memory O(samples).
 */
#ifndef SPHCOVER_RBUFFER_H
#define SPHCOVER_RBUFFER_H

#include "cover/HemisphereGrid.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace sphcover
{

struct Patch;
class RayCaster;
struct CullingStatistics;

/// How an R-buffer is filled (two fills of the same R-buffer,
/// Documentation/Pipeline.md#spherical-cover).
enum class RBufferFill
{
  /// Paper §4.3 Step 2: project each candidate patch into (theta, phi) with a depth test.
  Projection,
  /// Cast the sample rays through a tessellation of the patches (Intel Embree 3).
  RayCasting
};

const char* RBufferFillName(RBufferFill fill);

struct RBufferFillOptions
{
  /// Record directions in which a concave receiver patch sees itself (h_ii), see the file
  /// comment. Off: paper §3.3's convention, those directions stay empty.
  bool CountSelfVisibility = true;
  /// Hits of the receiver's own patch nearer than this fraction of its Size() are P_i itself.
  double SelfExclusionFraction = 1e-3;
  /// A sample whose ray meets its surface with |cos| below this (within ~2.9 degrees of
  /// tangency) is grazing (ray fill only; see RBuffer::CellGrazing).
  double GrazingCosine = 0.05;
  /// Projection fill: deepest level of the quadtree that splits candidate patches into pieces.
  int MaxPieceDepth = 16;
  /// Ray fill: largest deviation of the tessellation from the exact patch, as a fraction of the
  /// patch's Size(); the angular error seen from a point at distance d is about this times
  /// Size()/d.
  double TessellationTolerance = 1e-3;
  /// Ray fill: refine the hits that give the cells their R on the exact Bezier patch by
  /// Newton's method (otherwise R is the tessellation's).
  bool RefineHits = true;
  /// Back sides hide what lies behind them (opaque surfaces); false: paper §4.2.1's culling of
  /// back-facing patches, which makes them transparent. See the file comment.
  bool BackFacesOcclude = true;
  /// Classify() diffuses the cell vote's rounding error along each theta row (see the file
  /// comment): each source keeps its sampled coverage (Documentation/notes/r-buffer-vote.md).
  /// Off: the plain plurality vote, cell by cell (exactly reciprocal in symmetric
  /// configurations, the cells of CountSelfVisibility on and off complementary).
  bool DiffuseRounding = false;
  /// Ray fill: cast every cell's centre sample, then the other samples only of the cells whose
  /// centre and 8 neighbouring centres do not all show one surface (or all nothing); the
  /// others are copies of the centre (see the file comment and RayCastFill.h): 22 % of the
  /// rays on the Cornell box at its settings (Documentation/notes/ray-casting.md). Off: every
  /// sample is a ray, as before. The projection fill ignores it.
  bool AdaptiveSampling = true;
  /**
   * Per surface (Patch::SurfaceIndex; empty or shorter: none) whether it is one side of a thin
   * pane (paper §5.4; Data/scenes/FORMAT.md "transmittance"; the loader makes a pane two
   * one-sided surfaces, the patch and its reversed copy). A pane's front side is a source like
   * any other; its back side is never met (it is the other copy's front): the rays pass it
   * whatever BackFacesOcclude says. What lies behind a pane is found by
   * RayCastFiller::FillBehindPanes. Ray fill only: the projection fill refuses panes.
   */
  std::vector<bool> PaneSurfaces;
  /**
   * Per surface (Patch::SurfaceIndex; empty or shorter: none) whether it is one side of a
   * two-sided surface (Surface::TwoSided; the loader makes it two one-sided surfaces, the patch
   * and its reversed copy, as for a pane). Each side is a receiver with its own hemispheres and
   * a source on its front (paper §3.3); its back side is never met, since the other copy's
   * front is at the same place: both fills let it pass whatever BackFacesOcclude says (the
   * projection fill projects neither a source nor an occluder of it), so every direction that
   * meets the surface finds the side it faces.
   */
  std::vector<bool> TwoSidedSurfaces;
  /// Ray fill with AdaptiveSampling: cast the rays 16 at a time as Embree packets
  /// (RayCaster::IntersectPacket, in the same order) instead of one by one.
  bool RayPackets = true;
};

class RBuffer
{
public:
  static constexpr int32_t NoSource = -1;
  /// Cell flags.
  static constexpr uint8_t CellTie = 1;     ///< the winner was decided by the tie rule
  static constexpr uint8_t CellGrazing = 2; ///< some sample met its surface at a grazing angle

  explicit RBuffer(const HemisphereGrid& grid);

  const HemisphereGrid& Grid() const { return *this->GridPointer; }

  /// Clears the samples and cells for receiver `receiver`.
  void Reset(std::size_t receiver);
  std::size_t Receiver() const { return this->ReceiverIndex; }

  // --- samples (written by the fills) -------------------------------------------------------
  int32_t SampleSource(std::size_t sample) const { return this->SampleSources[sample]; }
  /// Exact distance along the sample ray to its source, NaN where the fill did not compute it.
  float SampleDepth(std::size_t sample) const { return this->SampleDepths[sample]; }
  bool SampleGrazing(std::size_t sample) const { return this->SampleGrazings[sample] != 0; }
  void SetSample(std::size_t sample, int32_t source, float depth, bool grazing)
  {
    this->SampleSources[sample] = source;
    this->SampleDepths[sample] = depth;
    this->SampleGrazings[sample] = grazing ? 1 : 0;
  }

  /**
   * Coverage classification of every cell (see the file comment). `depthOf(sample, source)`
   * supplies the distance along a representative sample whose SampleDepth is NaN (the
   * projection fill computes it on demand by Newton's method). `groupOfSource[j]` is the
   * group (surface) of source j for the first round of the vote; without it every source is a
   * group of its own.
   */
  void Classify(const std::function<float(std::size_t sample, int32_t source)>& depthOf,
    const std::vector<int32_t>* groupOfSource = nullptr,
    bool diffuseRounding = false);

  // --- cells (after Classify) ------------------------------------------------------------------
  int32_t CellSource(int cell) const { return this->CellSources[static_cast<size_t>(cell)]; }
  float CellDepth(int cell) const { return this->CellDepths[static_cast<size_t>(cell)]; }
  uint8_t CellFlags(int cell) const { return this->CellFlagValues[static_cast<size_t>(cell)]; }
  /// Number of the cell's samples covered by its winning patch (by none if the cell is empty).
  int CellVotes(int cell) const { return this->CellVoteCounts[static_cast<size_t>(cell)]; }
  /// Sum of the measures of the cells that have a source.
  double CoveredProjectedSolidAngle() const;

  /**
   * Paper §4.3 Step 3 needs, per source j, how much of H_i the projection of Q_j would take
   * without occlusion, to compare with what it keeps. The projection fill provides it: pairs
   * (j, projected solid angle of the samples covered by Q_j's unoccluded projection), j
   * ascending. The ray fill does not (it sees nearest hits only).
   */
  bool HasUnoccluded() const { return this->HasUnoccludedValues; }
  const std::vector<std::pair<int32_t, float>>& UnoccludedProjectedSolidAngles() const
  {
    return this->Unoccluded;
  }
  void SetUnoccludedProjectedSolidAngles(std::vector<std::pair<int32_t, float>> values);

private:
  const HemisphereGrid* GridPointer;
  std::size_t ReceiverIndex = 0;
  std::vector<int32_t> SampleSources;
  std::vector<float> SampleDepths;
  std::vector<uint8_t> SampleGrazings;
  std::vector<int32_t> CellSources;
  std::vector<float> CellDepths;
  std::vector<uint8_t> CellFlagValues;
  std::vector<uint8_t> CellVoteCounts;
  bool HasUnoccludedValues = false;
  std::vector<std::pair<int32_t, float>> Unoccluded;
};

/**
 * @brief Fills R-buffers of the receivers of one environment (a list of patches); one object
 * per environment and fill method, shared by all threads: Fill() is const and thread-safe.
 */
class RBufferFiller
{
public:
  virtual ~RBufferFiller() = default;
  virtual RBufferFill Kind() const = 0;

  /**
   * Fills `buffer` for receiver `receiver` (an index into the patches): Reset, samples,
   * Classify. `culling`, when given, receives the candidate culling counts of this receiver
   * (projection fill; the ray fill culls nothing: rays simply miss what is below the tangent
   * plane and skip back faces).
   */
  virtual void Fill(std::size_t receiver, RBuffer& buffer, CullingStatistics* culling) const = 0;

  /// Transient bytes the filler holds for the environment (the ray fill's tessellation and BVH
  /// estimate; 0 for the projection fill).
  virtual std::size_t EnvironmentBytes() const = 0;

  /**
   * The filler of the given kind. The patches and grid must outlive it. The ray fill casts
   * against `rays` when given (RayCastFiller), else builds its Embree scene here (this can take
   * a while for large environments); the projection fill ignores `rays`. Throws
   * std::runtime_error if Embree cannot be initialised.
   */
  static std::unique_ptr<RBufferFiller> Create(RBufferFill kind,
    const std::vector<Patch>& patches,
    const HemisphereGrid& grid,
    const RBufferFillOptions& options = {},
    std::shared_ptr<const RayCaster> rays = nullptr);
};

} // namespace sphcover

#endif
