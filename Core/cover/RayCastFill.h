// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file RayCastFill.h
 * @brief The second R-buffer fill (Documentation/Pipeline.md#spherical-cover, paper §4.3 Step 2):
 * the sample rays of every cell are cast from P_i through the RayCaster's tessellation of the exact
 * patches, and the first front side hit is mapped back to its patch.
 *
 * Rays: origin P_i (a vertex of its own patch's tessellation, so a ray never starts inside one
 * of its triangles), the sample directions of HemisphereGrid in world coordinates, in the
 * order given below. A hit filter implements the visibility semantics of RBuffer.h: back
 * sides are skipped (traversal goes on behind them) unless BackFacesOcclude, and hits on the
 * receiver's own patch nearer than SelfExclusionFraction * Size() (all of them when
 * CountSelfVisibility is off) are P_i itself. A back side that occludes leaves its sample empty.
 * A sample is grazing when the exact normal at the hit's (u, v) meets the ray with
 * |cos| < GrazingCosine (a planar patch's normal is its plane's: evaluated only near the
 * threshold). With RefineHits, R is refined on the exact patch (RayCaster::Refine) for the
 * cells' representative samples only, when Classify asks for it; without, R is the
 * tessellation's.
 *
 * AdaptiveSampling (the default): first the centre sample of every cell
 * (HemisphereGrid::SamplesFromCentre()[0]), cells in row-major order. A cell is uniform when its
 * centre and the centres of its 8 neighbours (phi wraps around; rows 0 and ThetaBins-1 have
 * no row beyond them) show front sides of one surface (Patch::SurfaceIndex, the vote's first
 * round), or are all empty. A uniform cell's other samples are not cast: each is written as
 * its centre (same source and grazing flag, R NaN); every other cell's are cast, cells in
 * row-major order; with RayPackets the rays of both passes go in that order 16 at a time
 * through RayCaster::IntersectPacket (the same hits as one by one on every sample compared,
 * Testing/Core/cover/TestAdaptiveSampling.cxx). A uniform cell's representative sample is its
 * centre, so its R is the
 * centre's, exact. What the full sampling would see and this does not: a source (or a gap)
 * that meets no centre sample within a 3 x 3 block of cells, i.e. smaller than about a cell,
 * and within one surface a patch boundary inside a uniform cell (the cell goes to the patch
 * at its centre, not to the plurality of its samples). Without AdaptiveSampling every sample is
 * cast, in row-major sample order, as before. Either way the result depends on the receiver
 * only, never on the thread that fills it. Fill() is O(samples x log triangles) (adaptive:
 * O((cells + samples of the cells at boundaries) x log triangles)) and may run from several
 * threads.
 */
#ifndef SPHCOVER_RAYCASTFILL_H
#define SPHCOVER_RAYCASTFILL_H

#include "cover/RBuffer.h"
#include "geometry/RayCaster.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sphcover
{

/// The caster's view of the patches (their geometry and surface; the patches must outlive it).
std::vector<RayCastPatch> RayCastPatches(const std::vector<Patch>& patches);

/**
 * The projected solid angle through which the point `origin` with unit normal `normal` sees the
 * front side of `target` (patch `source` of `caster`), integrated over the patch: the integral
 * over it of V cos(theta_i) cos(theta_j) / r^2 dA by the midpoint rule on an n x n grid of its
 * (u, v), n = clamp(4 Size / |origin - target's centre|, minimumSide, 32) per side (finer when
 * it is near), the visibility V of each node by one ray from `origin` through `filter`: a node
 * counts when the ray's first accepted hit is `source`'s front side. Safe to call from several
 * threads.
 */
double VisibleProjectedSolidAngle(const RayCaster& caster,
  const glm::dvec3& origin,
  const glm::dvec3& normal,
  const RayFilter& filter,
  std::size_t source,
  const Patch& target,
  int minimumSide);
/**
 * VisibleProjectedSolidAngle seen through panes (paper §5.4), per band: a node's ray that meets
 * the front side of a patch with a non-zero transmittanceOfPatch[p] (null: none) goes on behind
 * it (cast again beyond it, at most MaxPanesPerRay panes), the node counting with the product of
 * the transmittances passed. The filter must pass the panes' back sides (their reversed copies'
 * fronts). With no pane on the way, every band is VisibleProjectedSolidAngle. A ray that still
 * meets a pane after MaxPanesPerRay of them does not count, and adds one to `*paneLimitRays`
 * (when given).
 */
glm::dvec3 VisibleProjectedSolidAngleThroughPanes(const RayCaster& caster,
  const glm::dvec3& origin,
  const glm::dvec3& normal,
  const RayFilter& filter,
  std::size_t source,
  const Patch& target,
  int minimumSide,
  const std::vector<glm::vec3>* transmittanceOfPatch,
  uint64_t* paneLimitRays = nullptr);
/// Most panes a node's ray goes through (VisibleProjectedSolidAngleThroughPanes); a ray that
/// meets more is counted in its `paneLimitRays`.
constexpr int MaxPanesPerRay = 8;

/// The caster's options among a fill's.
RayCasterOptions RayCastOptions(const RBufferFillOptions& options);

class RayCastFiller : public RBufferFiller
{
public:
  /**
   * Casts against `rays` when given: a RayCaster of these patches (RayCastPatches) with
   * RayCastOptions(options), built once and shared with the other users of the same patches
   * (the direct light, the memory estimate); builds its own otherwise. Throws what RayCaster
   * throws (patches beyond MaxRayCastCoordinate, Embree failing), std::invalid_argument when
   * `rays` holds another number of patches.
   */
  RayCastFiller(const std::vector<Patch>& patches,
    const HemisphereGrid& grid,
    const RBufferFillOptions& options,
    std::shared_ptr<const RayCaster> rays = nullptr);
  ~RayCastFiller() override;
  RayCastFiller(const RayCastFiller&) = delete;
  RayCastFiller& operator=(const RayCastFiller&) = delete;

  RBufferFill Kind() const override { return RBufferFill::RayCasting; }
  void Fill(std::size_t receiver, RBuffer& buffer, CullingStatistics* culling) const override;
  std::size_t EnvironmentBytes() const override;

  /// The tessellation the samples are cast against.
  const RayCaster& Caster() const { return *this->Rays; }

  /**
   * The projected solid angle through which `receiver`'s point P_i sees the patch `source`
   * (Q_j), integrated over Q_j instead of counted in cells (the free function above), with the
   * same filter as the samples (back sides pass unless BackFacesOcclude, P_i's own patch is
   * P_i). Used by SphericalCover for the regions of SphericalCoverOptions::MeasuredSurfaces.
   * Safe to call from several threads.
   */
  double VisibleProjectedSolidAngle(std::size_t receiver,
    std::size_t source,
    int minimumSide = 8) const;

  /// Whether the scene has panes, and whether `patch` is a pane's side
  /// (RBufferFillOptions::PaneSurfaces).
  bool HasPanes() const { return !this->PanePatch.empty(); }
  bool IsPane(std::size_t patch) const
  {
    return !this->PanePatch.empty() && this->PanePatch[patch] != 0;
  }

  /**
   * What `receiver`'s point sees behind `layer` >= 1 panes (paper §5.4): `behind` gets, in the
   * cells where `front` (layer - 1: Fill's buffer, or this function's for the layer before)
   * is won by a pane's side, for each of the cell's samples the surface its ray meets after
   * passing exactly `layer` panes' front sides (cast again from each pane met, the ray's own
   * path), with the tessellation's distance. A sample whose ray meets something else first (an
   * opaque surface, a back side, nothing) before `layer` panes takes the value of the cell's
   * first sample in HemisphereGrid::SamplesFromCentre() order that does get through (the cell
   * is seen through a pane: its samples vote only on what lies behind it); a cell none of
   * whose samples gets through stays empty, as do the cells `front` does not give to a pane.
   * Then Classify, as Fill. In a closed scene every cell won by a pane in `front` is covered in
   * `behind`, so the layers' measures agree (the white furnace with panes stays exact). Costs
   * layer + 1 rays per sample of those cells. Safe to call from several threads.
   */
  void FillBehindPanes(std::size_t receiver,
    const RBuffer& front,
    int layer,
    RBuffer& behind) const;

  /// A computed hemisphere lent to FillFromDonors: its patch and, per cell, its source
  /// (RBuffer::NoSource where none) and R.
  struct Donor
  {
    std::size_t Patch;
    const int32_t* CellSources;
    const float* CellDepths;
  };
  /// Two donors that bracket a receiver, at `T` in [0, 1] from A to B (the receiver's share of
  /// the way: |P_i - P_A| / (|P_i - P_A| + |P_i - P_B|)).
  struct DonorPair
  {
    Donor A;
    Donor B;
    double T;
  };
  /**
   * Fills `buffer` for `receiver` from its donors' hemispheres (paper §3.4; the plan is
   * HemisphereInterpolation.h), casting rays only where they do not tell. A pair is used when
   * its donors' frames are the receiver's (but for the origin: a flat surface) and the cells
   * where its two donors show different surfaces (or one nothing) measure at most
   * `maxDifference` of the hemisphere (projected solid angle). Each such pair is interpolated row
   * by row (InterpolateHemispheres); a cell where the pairs agree (every cell when there is one
   * pair), and which is not the receiver's own patch, takes that source and the pairs' mean R
   * without a ray. The other cells are cast as Fill casts them (their centres, then, with
   * `sampleBoundaryCells`, every sample of the cells at a change of surface; without, their
   * centres decide alone); no usable pair: Fill. Then Classify, as Fill. What this misses that
   * Fill sees: what both pairs (or the one pair) interpolate alike and wrongly, i.e. a source
   * that appears between the donors and is in neither. Needs AdaptiveSampling (without it
   * every sample is cast). Safe to call from several threads.
   */
  void FillFromDonors(std::size_t receiver,
    const std::vector<DonorPair>& pairs,
    double maxDifference,
    bool sampleBoundaryCells,
    RBuffer& buffer) const;

  /// Sample rays cast by all Fill() calls so far (a statistic: with AdaptiveSampling fewer
  /// than Fill() calls x SampleCount(); the same for any number of threads).
  std::uint64_t RaysCast() const;

private:
  /// One hemisphere's casting: frame, filter, the buffer and the hits' parameters per sample.
  struct SampleCast
  {
    const HemisphereFrame& Frame;
    RayFilter Filter;
    RBuffer& Buffer;
    double* U;
    double* V;
    float* T;
  };

  /// What FillFromDonors knows before the rays: per cell a source (NoSource: nothing; -2:
  /// unknown, to be cast) and its R.
  struct Prediction
  {
    std::vector<int32_t>& Source;
    std::vector<float>& Depth;
    bool SampleBoundaryCells;
  };
  /// Casts the samples of `receiver`'s hemisphere into `buffer` (sources, grazing flags, the
  /// tessellation's depths), all of them or adaptively, and keeps the hits' (u, v, t) for the
  /// refinement in Classify; the cells `prediction` (may be null) knows are not cast. Returns
  /// the number of rays cast.
  std::size_t CastSamples(std::size_t receiver,
    const HemisphereFrame& frame,
    RBuffer& buffer,
    const Prediction* prediction) const;
  /// Classify with the exact R of the representative samples (RefineHits).
  void ClassifyCells(const HemisphereFrame& frame, RBuffer& buffer) const;
  /// Samples waiting to be cast as one packet (RayPackets).
  struct PendingRays
  {
    int Count = 0;
    int Row[RayCaster::PacketSize];
    int Column[RayCaster::PacketSize];
    glm::dvec3 Direction[RayCaster::PacketSize];
  };
  /// Casts a sample now (without RayPackets) or queues it, casting the queue when it is full.
  void Queue(const SampleCast& cast, PendingRays& pending, int row, int column) const;
  /// Casts the queued samples as one packet and writes them.
  void Flush(const SampleCast& cast, PendingRays& pending) const;
  /// Casts one sample and writes it; returns the source it shows (NoSource when empty).
  int32_t CastSample(const SampleCast& cast, int row, int column) const;
  /// Writes a front-side hit into sample `sample`.
  void StoreHit(const SampleCast& cast,
    std::size_t sample,
    const TriangleHit& hit,
    const glm::dvec3& direction) const;
  /// Whether the unit `direction` meets the exact patch at the hit with |cos| < GrazingCosine.
  bool IsGrazing(const TriangleHit& hit, const glm::dvec3& direction) const;

  const std::vector<Patch>& Patches;
  const HemisphereGrid& Grid;
  RBufferFillOptions Options;
  std::vector<int32_t> SurfaceOfPatch;
  /// Per patch: the unit normal of its plane when it is planar, else zero (IsGrazing).
  std::vector<glm::dvec3> PlaneNormals;
  /// Per patch n . q of its plane (PlaneNormals; 0 for a patch that is not planar).
  std::vector<double> PlaneOffsets;
  /// Per patch 1 when it is a pane's side; empty when no patch is.
  std::vector<char> PanePatch;
  /// Per patch 1 when the rays pass its back side, which is its reversed copy's front: a pane's
  /// side or one side of a two-sided surface (RBufferFillOptions::TwoSidedSurfaces); empty when
  /// no patch is.
  std::vector<char> PassedBack;
  std::shared_ptr<const RayCaster> Rays;
  /// Per receiver RayFilter::RejectsAllNearer of its point's rays (ReceiverRejectsAllNearer):
  /// found once, as the measured lamp regions ask for it once per lamp patch a receiver sees.
  std::vector<float> RejectsAllNearer;
  mutable std::atomic<std::uint64_t> RayCount{ 0 };
};

} // namespace sphcover

#endif
