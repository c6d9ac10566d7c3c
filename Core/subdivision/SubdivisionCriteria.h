// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SubdivisionCriteria.h
 * @brief The subdivision criteria of paper §4.2, evaluated by range estimates over whole
 * patches (never by sampling), for one pair: a receiver's characteristic point P_i and a
 * source patch Q_j.
 *
 * Every criterion is a range test of a polynomial over the patch (BernsteinBounds.h), compared
 * with a tolerance relative to a scale taken at the patch centres, so a test can check each
 * verdict by sampling the same polynomial:
 *
 * - Hemispherical containment, §4.2.2: h(u,v) = N_i . (Q_j(u,v) - P_i), scale d = |P_j - P_i|.
 *   Below the horizon if h <= tol d everywhere (classified: no light, no split); contained if
 *   h >= -tol d everywhere; otherwise Q_j straddles the horizon and is split.
 * - Self-shadowing, §4.2.1: f(u,v) = N_j(u,v) . (Q_j(u,v) - P_i), where N_j = dQ/du x dQ/dv;
 *   f < 0 where P_i sees the front of Q_j. Scale s = |N_j(1/2,1/2)| d. Back-facing if
 *   f >= -tol s everywhere (classified; this includes a patch seen edge-on); front-facing if
 *   f <= tol s everywhere; otherwise Q_j has a silhouette as seen from P_i and is split.
 *   A two-sided source is never back-facing: only a silhouette splits it.
 * - Spherical shape, §4.2.3. Distance form (diffuse sources): the distance from P_i stays
 *   within a factor 1 -+ tol of d, (1-tol)^2 d^2 <= g(u,v) = |Q_j(u,v) - P_i|^2 <=
 *   (1+tol)^2 d^2. Normal form (mirror, phong and tabulated sources, whose radiance depends on
 *   the direction): the paper asks N^_j . (Q_j - P_i) to be nearly constant; we require the
 *   range of f to be narrower than tol s, i.e. the projected normal toward P_i varies by less
 *   than the tolerance over the patch (a flat patch seen obliquely satisfies the paper's form
 *   only after its distance variation is small, which is what this measures).
 * - Characterisability, §4.2.4: P_i characterises Q_i for receiving light from P_j if
 *   k(u,v) = N_i(u,v) . (Q_i(u,v) - P_j) is nearly constant: its range is narrower than
 *   tol |N_i(1/2,1/2)| d. Otherwise the receiver Q_i is split.
 *
 * A pair classified below the horizon or back-facing is never split (the paper's "fully facing
 * the other way"). Splits are further limited by the caller (MaxLevel, and no patch is split
 * once it projects to about one (theta,phi) cell: paper §4.3 note 2).
 *
 * Complexity: one pair costs at most four range bounds, O(m^2 n^2) each with Bernstein bounds
 * for patches of degree (m, n) (BernsteinBounds.h).
 */
#ifndef SPHCOVER_SUBDIVISIONCRITERIA_H
#define SPHCOVER_SUBDIVISIONCRITERIA_H

#include "geometry/BernsteinBounds.h"
#include "scene/Scene.h"
#include "subdivision/Patch.h"

#include <cstddef>
#include <string>

namespace sphcover
{

/// The criteria of paper §4.2: each can be switched off and has its own tolerance.
enum class Criterion
{
  SelfShadowing = 0,
  HemisphericalContainment = 1,
  SphericalShape = 2,
  Characterisability = 3
};
constexpr int NumberOfCriteria = 4;

/// Default budget of patches: every later stage grows with the patch count (the cover holds
/// one hemisphere per patch, the propagation shoots one column per patch). Why this value:
/// Documentation/notes/subdivision-budgets.md.
constexpr std::size_t DefaultMaximumPatches = 1000000;
/// Default budget of pair tests, the subdivision's time (about 10 to 25 minutes on two threads;
/// the rates behind it: Documentation/notes/subdivision-budgets.md).
constexpr std::size_t DefaultMaximumPairTests = 1000000000;
/// Default budget of the subdivision's memory (every patch made, with its derivative nets).
constexpr std::size_t DefaultSubdivisionMemoryBytes = std::size_t(8192) * 1024 * 1024;

struct SubdivisionSettings
{
  RangeMethod Method = RangeMethod::Bernstein;
  /// Deepest subdivision level (number of ternary splits from a surface), at most
  /// MaxSubdivisionLevel.
  int MaxLevel = 5;
  /// No patch is split once its interval box's diagonal is at most this fraction of the
  /// diagonal of the box of all surfaces (0: no such limit): the points go where the scene is
  /// large, not equally to every surface whatever its size.
  double MinPatchSize = 0.0;
  /// The subdivision stops with an error (std::length_error) rather than make more patches
  /// than this, or hold more bytes of patches than MemoryLimitBytes.
  std::size_t MaximumPatches = DefaultMaximumPatches;
  /// ... or test more pairs than this in all (its time).
  std::size_t MaximumPairTests = DefaultMaximumPairTests;
  std::size_t MemoryLimitBytes = DefaultSubdivisionMemoryBytes;
  /// The cover's grid: no patch is split once it projects to about one cell.
  int ThetaBins = 32;
  int PhiBins = 128;
  bool Enabled[NumberOfCriteria] = { true, true, true, true };
  double Tolerance[NumberOfCriteria] = { 0.02, 0.02, 0.02, 0.02 };

  bool IsEnabled(Criterion c) const { return this->Enabled[static_cast<int>(c)]; }
  double ToleranceOf(Criterion c) const { return this->Tolerance[static_cast<int>(c)]; }
  /// The angular size of one grid cell: min(pi/2 / ThetaBins, 2 pi / PhiBins).
  double CellAngle() const;
  /// Empty if the settings are usable, else what is wrong with them.
  std::string Problem() const;
};

/// One side of a pair as the criteria see it.
struct PatchView
{
  const BezierPatch* Geometry = nullptr;
  glm::dvec3 Point{ 0.0 };
  glm::dvec3 Normal{ 0.0, 0.0, 1.0 };
  /// |dQ/du x dQ/dv| at the parametric centre: the scale of f and k.
  double CentreNormalLength = 0.0;
  /// Diffuse sources use the distance form of §4.2.3, others the normal form.
  bool Diffuse = true;
};

/// The view of a patch; one-sided, as every surface is (a two-sided surface is two one-sided
/// surfaces, Scene.h's Surface::TwoSided).
PatchView ViewOf(const Patch& patch, bool diffuse);

/// How P_i and Q_j stand to each other.
enum class PairRelation
{
  BelowHorizon, ///< Q_j lies below the tangent plane of P_i (within tolerance)
  BackFacing,   ///< P_i sees only the back of Q_j (within tolerance)
  Exchanging    ///< light can pass from Q_j to P_i
};

struct PairAssessment
{
  PairRelation Relation = PairRelation::Exchanging;
  /// The criterion that asks for the source Q_j to be split (None: it need not be).
  SplitReason SplitSource = SplitReason::None;
  /// SplitReason::Characterisability if the receiver Q_i must be split.
  SplitReason SplitReceiver = SplitReason::None;
  /// Criteria verified to hold (within tolerance) over the whole patch, for each enabled
  /// criterion that was evaluated; used by tests to check soundness.
  bool Contained = false;
  bool FrontFacing = false;
  bool Spherical = false;
  bool Characterised = false;
};

/// Evaluates the criteria of paper §4.2 for receiver point P_i (of patch `receiver`) and
/// source patch `source`. Disabled criteria never ask for a split but still classify pairs
/// below the horizon or back-facing. When the caller knows that the source (or the receiver)
/// may not be split anyway (limits), the criteria that could only ask for that split are not
/// evaluated and their flags stay false.
PairAssessment AssessPair(const PatchView& receiver,
  const PatchView& source,
  const SubdivisionSettings& settings,
  bool sourceMaySplit = true,
  bool receiverMaySplit = true);

} // namespace sphcover

#endif
