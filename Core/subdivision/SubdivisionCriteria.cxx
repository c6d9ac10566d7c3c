// SPDX-License-Identifier: BSD-3-Clause
#include "subdivision/SubdivisionCriteria.h"

#include "math/Constants.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <sstream>

namespace sphcover
{

double SubdivisionSettings::CellAngle() const
{
  return std::min(HalfPi / this->ThetaBins, TwoPi / this->PhiBins);
}

std::string SubdivisionSettings::Problem() const
{
  std::ostringstream problem;
  if (this->MaxLevel < 0 || this->MaxLevel > MaxSubdivisionLevel)
  {
    problem << "MaxLevel must be >= 0 and at most " << MaxSubdivisionLevel
            << " (deeper patches are narrower than the double precision of the parameter "
               "domain), got "
            << this->MaxLevel;
  }
  else if (!(this->MinPatchSize >= 0.0 && this->MinPatchSize < 1.0))
  {
    problem << "MinPatchSize must be >= 0 and < 1 (a fraction of the scene's diagonal), got "
            << this->MinPatchSize;
  }
  else if (this->MaximumPatches < 1)
  {
    problem << "MaximumPatches must be >= 1";
  }
  else if (this->ThetaBins < 1 || this->PhiBins < 1)
  {
    problem << "ThetaBins and PhiBins must be >= 1, got " << this->ThetaBins << " and "
            << this->PhiBins;
  }
  else
  {
    const char* names[NumberOfCriteria] = { "SelfShadowingTolerance",
      "ContainmentTolerance",
      "SphericalShapeTolerance",
      "CharacterisabilityTolerance" };
    for (int c = 0; c < NumberOfCriteria; ++c)
    {
      if (!(this->Tolerance[c] >= MinimumTolerance) || !std::isfinite(this->Tolerance[c]))
      {
        // Below MinimumTolerance the rounding of the range bounds decides (see its comment).
        problem << names[c] << " must be a finite number >= " << MinimumTolerance << ", got "
                << this->Tolerance[c];
        break;
      }
    }
  }
  return problem.str();
}

PatchView ViewOf(const Patch& patch, bool diffuse)
{
  PatchView view;
  view.Geometry = &patch.Geometry;
  view.Point = patch.Point;
  view.Normal = patch.Normal;
  view.CentreNormalLength = glm::length(patch.Geometry.UnnormalizedNormal(0.5, 0.5));
  view.Diffuse = diffuse;
  return view;
}

PairAssessment AssessPair(const PatchView& receiver,
  const PatchView& source,
  const SubdivisionSettings& settings,
  bool sourceMaySplit,
  bool receiverMaySplit)
{
  const UVRect whole = UVRect::Unit();
  const RangeMethod method = settings.Method;
  const double distance = glm::length(source.Point - receiver.Point);
  PairAssessment result;

  // §4.2.2 hemispherical containment: height of Q_j over the tangent plane of P_i.
  const double containmentTolerance =
    settings.ToleranceOf(Criterion::HemisphericalContainment) * distance;
  const Interval height =
    RangeOfHeightAbovePlane(*source.Geometry, whole, receiver.Point, receiver.Normal, method);
  const bool below = height.Upper() <= containmentTolerance;
  result.Contained = height.Lower() >= -containmentTolerance;

  // §4.2.1 self-shadowing: which side of Q_j P_i sees, f < 0 on the front.
  const double facingTolerance =
    settings.ToleranceOf(Criterion::SelfShadowing) * source.CentreNormalLength * distance;
  const Interval facing = RangeOfFacing(*source.Geometry, whole, receiver.Point, method);
  const bool frontOnly = facing.Upper() <= facingTolerance;
  const bool backOnly = facing.Lower() >= -facingTolerance;
  result.FrontFacing = frontOnly;

  // Classified, not split: no light passes from Q_j to P_i.
  if (below)
  {
    result.Relation = PairRelation::BelowHorizon;
    return result;
  }
  if (backOnly)
  {
    result.Relation = PairRelation::BackFacing;
    return result;
  }
  result.Relation = PairRelation::Exchanging;

  // A silhouette, then the horizon.
  if (!sourceMaySplit)
  {
    // No split of Q_j can be asked for.
  }
  else if (settings.IsEnabled(Criterion::SelfShadowing) && !frontOnly && !backOnly)
  {
    result.SplitSource = SplitReason::SelfShadowing;
  }
  else if (settings.IsEnabled(Criterion::HemisphericalContainment) && !result.Contained)
  {
    result.SplitSource = SplitReason::HemisphericalContainment;
  }

  // §4.2.3 spherical shape of Q_j around P_i: only worth evaluating if it could decide a split.
  const double shapeTolerance = settings.ToleranceOf(Criterion::SphericalShape);
  if (!sourceMaySplit || result.SplitSource != SplitReason::None)
  {
    // Not evaluated: Spherical stays false.
  }
  else if (source.Diffuse)
  {
    const Interval squaredDistance =
      RangeOfSquaredDistance(*source.Geometry, whole, receiver.Point, method);
    const double lower = (1.0 - shapeTolerance) * distance;
    const double upper = (1.0 + shapeTolerance) * distance;
    result.Spherical = squaredDistance.Lower() >= (lower > 0.0 ? lower * lower : 0.0) &&
      squaredDistance.Upper() <= upper * upper;
  }
  else
  {
    result.Spherical = facing.Width() <= shapeTolerance * source.CentreNormalLength * distance;
  }
  if (sourceMaySplit && result.SplitSource == SplitReason::None &&
    settings.IsEnabled(Criterion::SphericalShape) && !result.Spherical)
  {
    result.SplitSource = SplitReason::SphericalShape;
  }

  // §4.2.4 characterisability of Q_i by P_i for light from P_j.
  if (!receiverMaySplit)
  {
    return result;
  }
  const Interval receiving = RangeOfFacing(*receiver.Geometry, whole, source.Point, method);
  result.Characterised = receiving.Width() <=
    settings.ToleranceOf(Criterion::Characterisability) * receiver.CentreNormalLength * distance;
  if (settings.IsEnabled(Criterion::Characterisability) && !result.Characterised)
  {
    result.SplitReceiver = SplitReason::Characterisability;
  }
  return result;
}

} // namespace sphcover
