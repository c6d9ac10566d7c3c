// SPDX-License-Identifier: BSD-3-Clause
#include "cover/ProjectionFill.h"

#include "math/Constants.h"

#include "cover/CandidateCulling.h"
#include "geometry/BernsteinBounds.h"
#include "geometry/DeCasteljau.h"
#include "geometry/RayPatchIntersection.h"
#include "subdivision/Patch.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace sphcover
{

namespace
{
/// sin(45 degrees): the largest bounding-cone half-angle of an accepted piece.
constexpr double MaxConeSine = 0.70710678118654752;
/// cos(60 degrees): the longest great-circle arc of a boundary polyline.
constexpr double MinArcCosine = 0.5;
/// Deepest recursion of the adaptive boundary sampling of one edge.
constexpr int MaxEdgeLevel = 24;
/// Side of the grid of directions that starts Newton's method on a piece.
constexpr int GuessGrid = 5;

/// One rectangle of a source patch accepted for projection.
struct Piece
{
  int32_t Source = 0;
  /// The piece turns its back to P_i: it hides what lies behind it but is no source.
  bool Occluder = false;
  UVRect Rect;
  double DepthLo = 0.0;
  double DepthHi = 0.0;
  /// The last Newton solution on this piece: neighbouring samples start from it.
  bool HasGuess = false;
  double GuessU = 0.0;
  double GuessV = 0.0;
};

/// A signed crossing of the boundary with a sample row's cone.
struct RowCrossing
{
  int SampleRow;
  double Phi;
  int Delta;
};

/// A signed crossing of the boundary with the half-plane phi = 0.
struct MeridianCrossing
{
  double Theta;
  int Delta;
};

/// A run of covered samples of one sample row: columns [First, Last).
struct Span
{
  int32_t PieceIndex;
  int32_t SampleRow;
  int32_t First;
  int32_t Last;
};

double AngleBetween(const glm::dvec3& a, const glm::dvec3& b)
{
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

/// All the state of one receiver's projection fill.
class ReceiverProjection
{
public:
  ReceiverProjection(const std::vector<Patch>& patches,
    const HemisphereGrid& grid,
    const RBufferFillOptions& options,
    const std::vector<int32_t>& surfaceOfPatch,
    std::size_t receiver)
    : Patches(patches)
    , Grid(grid)
    , Options(options)
    , SurfaceOfPatch(surfaceOfPatch)
    , Receiver(receiver)
    , Frame(HemisphereFrame::OfPatch(patches[receiver]))
  {
    this->SampleSpacing =
      std::min(grid.ThetaStep() / grid.SamplesTheta(), grid.PhiStep() / grid.SamplesPhi());
    this->BoundaryTolerance = 5e-3 * this->SampleSpacing;
    const double exclusion = options.SelfExclusionFraction * patches[receiver].Geometry.Size();
    this->SelfExclusionSquared = exclusion * exclusion;
    // sin(elevation) of the lowest sample row, slightly reduced against rounding.
    this->LowestSampleSine = 0.999 * grid.SampleCosTheta(grid.SampleRows() - 1);
    this->SampleTheta.resize(static_cast<size_t>(grid.SampleRows()));
    for (int row = 0; row < grid.SampleRows(); ++row)
    {
      this->SampleTheta[static_cast<size_t>(row)] =
        std::atan2(grid.SampleSinTheta(row), grid.SampleCosTheta(row));
    }
  }

  void Run(RBuffer& buffer, CullingStatistics& culling)
  {
    this->CollectPieces(culling);
    this->SamplePiece.assign(this->Grid.SampleCount(), -1);
    this->DepthLo.assign(this->Grid.SampleCount(), 0.0);
    this->DepthHi.assign(this->Grid.SampleCount(), 0.0);
    for (size_t p = 0; p < this->Pieces.size(); ++p)
    {
      this->ProjectPiece(static_cast<int32_t>(p));
    }
    buffer.Reset(this->Receiver);
    for (std::size_t s = 0; s < this->Grid.SampleCount(); ++s)
    {
      const int32_t piece = this->SamplePiece[s];
      if (piece >= 0 && !this->Pieces[static_cast<size_t>(piece)].Occluder)
      {
        const bool exact = this->DepthLo[s] == this->DepthHi[s];
        buffer.SetSample(s,
          this->Pieces[static_cast<size_t>(piece)].Source,
          exact ? static_cast<float>(this->DepthLo[s]) : std::numeric_limits<float>::quiet_NaN(),
          false);
      }
    }
    buffer.Classify(
      [this](std::size_t sample, int32_t)
      {
        const int32_t piece = this->SamplePiece[sample];
        double depth = this->ExactDepth(piece, sample);
        if (std::isnan(depth))
        {
          const Piece& p = this->Pieces[static_cast<size_t>(piece)];
          depth = 0.5 * (p.DepthLo + p.DepthHi);
        }
        return static_cast<float>(depth);
      },
      &this->SurfaceOfPatch,
      this->Options.DiffuseRounding);
    buffer.SetUnoccludedProjectedSolidAngles(this->MeasureUnoccluded());
  }

private:
  // --- 1. culling and pieces -------------------------------------------------------------------
  void CollectPieces(CullingStatistics& culling)
  {
    const glm::dvec3& point = this->Frame.Origin;
    const glm::dvec3& normal = this->Frame.Normal;
    for (size_t j = 0; j < this->Patches.size(); ++j)
    {
      const bool self = j == this->Receiver;
      if (self && !this->Options.CountSelfVisibility)
      {
        continue;
      }
      ++culling.Candidates;
      const BezierPatch& patch = this->Patches[j].Geometry;
      const CandidateClass whole = ClassifyCandidate(patch, UVRect::Unit(), point, normal);
      if (whole == CandidateClass::BelowTangentPlane)
      {
        ++culling.BelowTangentPlane;
        continue;
      }
      const size_t before = this->Pieces.size();
      // P_i of one side of a two-sided surface lies on the other side too: near P_i, that side
      // is P_i itself (the ray fill's rule).
      const bool nearIsSelf = self || (this->IsTwoSided(this->Receiver) && this->IsTwoSided(j));
      if (whole == CandidateClass::BackFacing)
      {
        ++culling.BackFacing;
        if (!this->BackOccludes(j))
        {
          continue;
        }
        this->SplitIntoPieces(static_cast<int32_t>(j), nearIsSelf, whole);
        culling.Occluders += this->Pieces.size() - before;
        continue;
      }
      ++culling.Kept;
      this->SplitIntoPieces(static_cast<int32_t>(j), nearIsSelf, whole);
      culling.Pieces += this->Pieces.size() - before;
    }
    // Nearest depth range first: later pieces mostly lose their depth test outright.
    std::sort(this->Pieces.begin(),
      this->Pieces.end(),
      [](const Piece& a, const Piece& b)
      {
        return std::tie(a.DepthLo, a.Source, a.Rect.V0, a.Rect.U0) <
          std::tie(b.DepthLo, b.Source, b.Rect.V0, b.Rect.U0);
      });
  }

  /// Whether patch j is one side of a two-sided surface (RBufferFillOptions::TwoSidedSurfaces).
  bool IsTwoSided(size_t j) const
  {
    const size_t surface = static_cast<size_t>(this->SurfaceOfPatch[j]);
    return surface < this->Options.TwoSidedSurfaces.size() &&
      this->Options.TwoSidedSurfaces[surface];
  }

  /// Whether patch j's back side hides what lies behind it: not a two-sided surface's side, whose
  /// back is the other side's front at the same place (a source there, projected as such).
  bool BackOccludes(size_t j) const
  {
    return this->Options.BackFacesOcclude && !this->IsTwoSided(j);
  }

  bool CentreFaces(const BezierPatch& patch, const UVRect& rect) const
  {
    const double u = rect.CenterU();
    const double v = rect.CenterV();
    return glm::dot(patch.UnnormalizedNormal(u, v), patch.Evaluate(u, v) - this->Frame.Origin) <
      0.0;
  }

  void SplitIntoPieces(int32_t source, bool self, CandidateClass wholeClass)
  {
    const BezierPatch& patch = this->Patches[static_cast<size_t>(source)].Geometry;
    const glm::dvec3& point = this->Frame.Origin;
    const bool backOccludes = this->BackOccludes(static_cast<size_t>(source));
    struct Node
    {
      UVRect Rect;
      int Depth;
    };
    std::vector<Node> stack{ { UVRect::Unit(), 0 } };
    while (!stack.empty())
    {
      const Node node = stack.back();
      stack.pop_back();
      const UVRect& rect = node.Rect;
      const CandidateClass cls =
        node.Depth == 0 ? wholeClass : ClassifyCandidate(patch, rect, point, this->Frame.Normal);
      if (cls == CandidateClass::BelowTangentPlane ||
        (cls == CandidateClass::BackFacing && !backOccludes))
      {
        continue;
      }
      const Interval squared = RangeOfSquaredDistance(patch, rect, point);
      const bool canSplit = node.Depth < this->Options.MaxPieceDepth;
      // Every direction to the rectangle has sin(elevation) = h / |Q - P| <= h_max / |Q - P|_min;
      // below the lowest sample row it covers no sample. This prunes the rectangles near the
      // horizon, notably those of a concave receiver patch around P_i itself.
      if (squared.Lower() > 0.0)
      {
        const double height =
          RangeOfHeightAbovePlane(patch, rect, point, this->Frame.Normal).Upper();
        if (height < this->LowestSampleSine * std::sqrt(squared.Lower()))
        {
          continue;
        }
      }
      if (self && squared.Lower() <= this->SelfExclusionSquared)
      {
        // Near P_i itself: keep splitting until the rectangle lies within the exclusion radius.
        if (squared.Upper() > this->SelfExclusionSquared && canSplit)
        {
          this->PushQuarters(stack, rect, node.Depth);
        }
        continue;
      }
      const IntervalVec3 box = RangeOfPosition(patch, rect);
      const glm::dvec3 lower(box.X.Lower(), box.Y.Lower(), box.Z.Lower());
      const glm::dvec3 upper(box.X.Upper(), box.Y.Upper(), box.Z.Upper());
      const glm::dvec3 centre = 0.5 * (lower + upper);
      const double radius = 0.5 * glm::length(upper - lower);
      const double distance = glm::length(centre - point);
      const bool coneFits = distance > radius && radius <= MaxConeSine * distance;
      const bool tiny =
        distance > radius && std::asin(radius / distance) <= 0.5 * this->SampleSpacing;
      bool accept = false;
      bool occluder = cls == CandidateClass::BackFacing;
      if ((cls == CandidateClass::FrontFacing || cls == CandidateClass::BackFacing) && coneFits)
      {
        accept = true;
      }
      else if ((cls == CandidateClass::Undecided && tiny) || !canSplit)
      {
        // A silhouette piece below half a sample spacing (or the depth limit): its fold is
        // invisible at the sample resolution; its centre decides which side P_i sees.
        occluder = cls == CandidateClass::BackFacing ||
          (cls == CandidateClass::Undecided && !this->CentreFaces(patch, rect));
        accept = coneFits && (!occluder || backOccludes);
      }
      else
      {
        this->PushQuarters(stack, rect, node.Depth);
        continue;
      }
      if (accept)
      {
        Piece piece;
        piece.Source = source;
        piece.Occluder = occluder;
        piece.Rect = rect;
        piece.DepthLo = std::sqrt(std::max(squared.Lower(), 0.0));
        piece.DepthHi = std::sqrt(squared.Upper());
        this->Pieces.push_back(piece);
      }
    }
  }

  template<typename Stack>
  static void PushQuarters(Stack& stack, const UVRect& rect, int depth)
  {
    const double um = rect.CenterU();
    const double vm = rect.CenterV();
    // Pushed in reverse so that the (u0, v0) quarter is processed first.
    stack.push_back({ { um, rect.U1, vm, rect.V1 }, depth + 1 });
    stack.push_back({ { rect.U0, um, vm, rect.V1 }, depth + 1 });
    stack.push_back({ { um, rect.U1, rect.V0, vm }, depth + 1 });
    stack.push_back({ { rect.U0, um, rect.V0, vm }, depth + 1 });
  }

  // --- 2. boundary -----------------------------------------------------------------------------
  glm::dvec3 LocalDirectionTo(const BezierPatch& patch, double u, double v) const
  {
    return this->LocalDirectionTo(patch.Evaluate(u, v));
  }

  /// Angular deviation of x from the great-circle arc a..b (large if beyond its ends).
  static double DeviationFromArc(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& x)
  {
    const glm::dvec3 g = glm::cross(a, b);
    const double length = glm::length(g);
    if (length < 1e-12)
    {
      return std::max(AngleBetween(a, x), AngleBetween(b, x));
    }
    const glm::dvec3 n = g / length;
    if (glm::dot(glm::cross(a, x), n) < 0.0 || glm::dot(glm::cross(x, b), n) < 0.0)
    {
      return Pi;
    }
    return std::asin(std::min(1.0, std::fabs(glm::dot(x, n))));
  }

  /// An edge of a piece as a Bezier curve in its own parameter t in [0, 1], oriented
  /// counter-clockwise around the piece.
  struct EdgeCurve
  {
    glm::dvec3 Points[BezierPatch::MaxDegree + 1];
    int Degree = 0;

    glm::dvec3 Evaluate(double t) const
    {
      glm::dvec3 work[BezierPatch::MaxDegree + 1];
      std::copy(this->Points, this->Points + this->Degree + 1, work);
      return DeCasteljauPoint(work, 1, this->Degree, t);
    }
  };

  /// The isoparametric curve of the patch at v = fixed (alongU) or u = fixed, restricted to
  /// [from, to] of the other parameter (reversed when from > to).
  static EdgeCurve MakeEdge(const BezierPatch& patch,
    bool alongU,
    double fixed,
    double from,
    double to)
  {
    const int m = patch.DegreeU();
    const int n = patch.DegreeV();
    const std::vector<glm::dvec3>& net = patch.ControlPoints();
    EdgeCurve curve;
    glm::dvec3 line[BezierPatch::MaxDegree + 1];
    if (alongU)
    {
      curve.Degree = m;
      for (int i = 0; i <= m; ++i)
      {
        for (int j = 0; j <= n; ++j)
        {
          line[j] = net[static_cast<size_t>(j * (m + 1) + i)];
        }
        curve.Points[i] = DeCasteljauPoint(line, 1, n, fixed);
      }
    }
    else
    {
      curve.Degree = n;
      for (int j = 0; j <= n; ++j)
      {
        for (int i = 0; i <= m; ++i)
        {
          line[i] = net[static_cast<size_t>(j * (m + 1) + i)];
        }
        curve.Points[j] = DeCasteljauPoint(line, 1, m, fixed);
      }
    }
    RestrictCurve(curve.Points, 1, curve.Degree, std::min(from, to), std::max(from, to));
    if (from > to)
    {
      std::reverse(curve.Points, curve.Points + curve.Degree + 1);
    }
    return curve;
  }

  glm::dvec3 LocalDirectionTo(const glm::dvec3& point) const
  {
    const glm::dvec3 local = this->Frame.ToLocal(point - this->Frame.Origin);
    const double length = glm::length(local);
    return length > 0.0 ? local / length : glm::dvec3(0.0, 0.0, 1.0);
  }

  void SampleEdge(const EdgeCurve& edge,
    double t0,
    const glm::dvec3& d0,
    double t1,
    const glm::dvec3& d1,
    int level)
  {
    bool fine = glm::dot(d0, d1) >= MinArcCosine;
    if (fine)
    {
      for (const double q : { 0.5, 0.25, 0.75 })
      {
        if (DeviationFromArc(d0, d1, this->LocalDirectionTo(edge.Evaluate(t0 + q * (t1 - t0)))) >
          this->BoundaryTolerance)
        {
          fine = false;
          break;
        }
      }
    }
    if (fine || level >= MaxEdgeLevel)
    {
      this->Boundary.push_back(d1);
      return;
    }
    const double tm = 0.5 * (t0 + t1);
    const glm::dvec3 dm = this->LocalDirectionTo(edge.Evaluate(tm));
    this->SampleEdge(edge, t0, d0, tm, dm, level + 1);
    this->SampleEdge(edge, tm, dm, t1, d1, level + 1);
  }

  void BuildBoundary(const Piece& piece)
  {
    const BezierPatch& patch = this->Patches[static_cast<size_t>(piece.Source)].Geometry;
    const UVRect& r = piece.Rect;
    // Counter-clockwise in (u, v): bottom, right, top (backwards), left (backwards).
    const EdgeCurve edges[4] = { MakeEdge(patch, true, r.V0, r.U0, r.U1),
      MakeEdge(patch, false, r.U1, r.V0, r.V1),
      MakeEdge(patch, true, r.V1, r.U1, r.U0),
      MakeEdge(patch, false, r.U0, r.V1, r.V0) };
    glm::dvec3 corners[4];
    for (int k = 0; k < 4; ++k)
    {
      corners[k] = this->LocalDirectionTo(edges[k].Points[0]);
    }
    this->Boundary.clear();
    this->Boundary.push_back(corners[0]);
    for (int k = 0; k < 4; ++k)
    {
      // Each edge appends its points after its start; the start is the previous edge's end.
      this->SampleEdge(edges[k], 0.0, corners[k], 1.0, corners[(k + 1) % 4], 0);
    }
    this->Boundary.pop_back(); // the closing point repeats the first
  }

  // --- 3. region fill --------------------------------------------------------------------------
  /// First sample row with theta >= theta (SampleRows() if none).
  int FirstRowAtOrBelow(double theta) const
  {
    return static_cast<int>(
      std::lower_bound(this->SampleTheta.begin(), this->SampleTheta.end(), theta) -
      this->SampleTheta.begin());
  }

  /// Adds the crossings of the chord a..b (a great-circle arc) with the sample rows' cones.
  void CrossRows(const glm::dvec3& a, const glm::dvec3& b)
  {
    double thetaA = std::atan2(std::hypot(a.x, a.y), a.z);
    double thetaB = std::atan2(std::hypot(b.x, b.y), b.z);
    double lo = std::min(thetaA, thetaB);
    double hi = std::max(thetaA, thetaB);
    const glm::dvec3 g = glm::cross(a, b);
    const double gLength = glm::length(g);
    if (gLength > 1e-300)
    {
      // The points of the great circle nearest to and farthest from N; if one of them lies
      // inside the arc, theta has an interior extremum there.
      const glm::dvec3 n = g / gLength;
      glm::dvec3 m(-n.z * n.x, -n.z * n.y, 1.0 - n.z * n.z);
      const double mLength = glm::length(m);
      if (mLength > 1e-300)
      {
        m /= mLength;
        for (const glm::dvec3& e : { m, -m })
        {
          if (glm::dot(glm::cross(a, e), g) > 0.0 && glm::dot(glm::cross(e, b), g) > 0.0)
          {
            const double theta = std::acos(std::min(1.0, std::max(-1.0, e.z)));
            lo = std::min(lo, theta);
            hi = std::max(hi, theta);
          }
        }
      }
    }
    this->ThetaLo = std::min(this->ThetaLo, lo);
    this->ThetaHi = std::max(this->ThetaHi, hi);
    if (lo > HalfPi)
    {
      return;
    }
    const int first = this->FirstRowAtOrBelow(lo);
    const int rows = this->Grid.SampleRows();
    const glm::dvec3 ab = b - a;
    const double ab2 = glm::dot(ab, ab);
    const double aab = glm::dot(a, ab);
    const double aa = glm::dot(a, a);
    for (int row = first; row < rows && this->SampleTheta[static_cast<size_t>(row)] <= hi; ++row)
    {
      const double c = this->Grid.SampleCosTheta(row);
      // Inside the cone (theta < theta_s) at the ends, decided once per vertex and row so that
      // consecutive arcs agree exactly on their shared vertex.
      const bool insideA = a.z > c;
      const bool insideB = b.z > c;
      // F(l) = z(l)^2 - c^2 |p(l)|^2 along p(l) = a + l (b - a), with z(l) > 0.
      const double qa = ab.z * ab.z - c * c * ab2;
      const double qb = 2.0 * (a.z * ab.z - c * c * aab);
      const double qc = a.z * a.z - c * c * aa;
      double roots[2];
      int count = 0;
      const double discriminant = qb * qb - 4.0 * qa * qc;
      if (std::fabs(qa) > 1e-300 && discriminant >= 0.0)
      {
        const double q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
        roots[count++] = q / qa;
        if (q != 0.0)
        {
          roots[count++] = qc / q;
        }
      }
      else if (qb != 0.0)
      {
        roots[count++] = -qc / qb;
      }
      // Keep the roots on the upper nappe (z > 0).
      int kept = 0;
      for (int k = 0; k < count; ++k)
      {
        if (a.z + roots[k] * ab.z > 0.0 && std::isfinite(roots[k]))
        {
          roots[kept++] = roots[k];
        }
      }
      count = kept;
      if (count == 2 && roots[1] < roots[0])
      {
        std::swap(roots[0], roots[1]);
      }
      if (insideA != insideB)
      {
        // Exactly one crossing: the root nearest to [0, 1].
        double best = 0.5;
        double bestDistance = std::numeric_limits<double>::infinity();
        for (int k = 0; k < count; ++k)
        {
          const double distance = std::max({ 0.0, -roots[k], roots[k] - 1.0 });
          if (distance < bestDistance)
          {
            bestDistance = distance;
            best = roots[k];
          }
        }
        best = std::min(1.0, std::max(0.0, best));
        this->AddRowCrossing(row, a + best * ab, insideA ? +1 : -1);
      }
      else if (count == 2 && roots[0] > 0.0 && roots[1] < 1.0 && roots[0] < roots[1])
      {
        // The arc dips across the row and back (or rises and returns).
        this->AddRowCrossing(row, a + roots[0] * ab, insideA ? +1 : -1);
        this->AddRowCrossing(row, a + roots[1] * ab, insideA ? -1 : +1);
      }
    }
  }

  void AddRowCrossing(int row, const glm::dvec3& p, int delta)
  {
    // The side of the seam is decided by the sign of y exactly as CrossMeridian decides it: a
    // point with y < 0 lies at the end of the row (phi in (pi, 2 pi], 2 pi included when y is
    // a rounding error below 0), one with y >= 0 at its start. Folding 2 pi back to 0 would
    // put a crossing on the wrong side of the seam and fill the complement of the row.
    double phi = std::atan2(p.y, p.x);
    if (p.y < 0.0)
    {
      phi = std::max(phi, -Pi) + TwoPi;
    }
    else
    {
      phi = std::max(phi, 0.0);
    }
    this->RowCrossings.push_back({ row, phi, delta });
  }

  /// The crossing of the chord a..b with the half-plane y = 0, x > 0 (phi = 0), if any.
  void CrossMeridian(const glm::dvec3& a, const glm::dvec3& b)
  {
    const bool aBelow = a.y < 0.0;
    const bool bBelow = b.y < 0.0;
    if (aBelow == bBelow)
    {
      return;
    }
    const double l = a.y / (a.y - b.y);
    const glm::dvec3 p = a + l * (b - a);
    if (!(p.x > 0.0))
    {
      return;
    }
    // Crossing from y < 0 to y > 0 turns once more around N (+1 to the axis winding); on the
    // path down the meridian it lowers the winding number by one.
    const int turn = aBelow ? +1 : -1;
    this->AxisWinding += turn;
    this->Meridian.push_back({ std::atan2(p.x, p.z), -turn });
  }

  void ProjectPiece(int32_t pieceIndex)
  {
    const Piece& piece = this->Pieces[static_cast<size_t>(pieceIndex)];
    this->BuildBoundary(piece);
    this->RowCrossings.clear();
    this->Meridian.clear();
    this->AxisWinding = 0;
    this->ThetaLo = Pi;
    this->ThetaHi = 0.0;
    const size_t n = this->Boundary.size();
    for (size_t k = 0; k < n; ++k)
    {
      const glm::dvec3& a = this->Boundary[k];
      const glm::dvec3& b = this->Boundary[(k + 1) % n];
      this->CrossRows(a, b);
      this->CrossMeridian(a, b);
    }
    int windingAtPole = 0;
    if (this->AxisWinding != 0)
    {
      // The region holds N or -N; the bounding cone tells which (it is at most 45 degrees).
      const BezierPatch& patch = this->Patches[static_cast<size_t>(piece.Source)].Geometry;
      const IntervalVec3 box = RangeOfPosition(patch, piece.Rect);
      const glm::dvec3 lower(box.X.Lower(), box.Y.Lower(), box.Z.Lower());
      const glm::dvec3 upper(box.X.Upper(), box.Y.Upper(), box.Z.Upper());
      const glm::dvec3 axis = 0.5 * (lower + upper) - this->Frame.Origin;
      if (glm::dot(axis, this->Frame.Normal) <= 0.0)
      {
        return; // -N: the region lies below the horizon
      }
      windingAtPole = this->AxisWinding;
    }
    if (this->ThetaLo > HalfPi)
    {
      return;
    }
    std::sort(this->RowCrossings.begin(),
      this->RowCrossings.end(),
      [](const RowCrossing& x, const RowCrossing& y)
      { return std::tie(x.SampleRow, x.Phi) < std::tie(y.SampleRow, y.Phi); });
    std::sort(this->Meridian.begin(),
      this->Meridian.end(),
      [](const MeridianCrossing& x, const MeridianCrossing& y) { return x.Theta < y.Theta; });
    const int rowBegin = windingAtPole != 0 ? 0 : this->FirstRowAtOrBelow(this->ThetaLo);
    const int rowEnd = std::min(this->Grid.SampleRows(), this->FirstRowAtOrBelow(this->ThetaHi));
    size_t nextCrossing = 0;
    size_t nextMeridian = 0;
    int winding = windingAtPole;
    for (int row = rowBegin; row < rowEnd; ++row)
    {
      const double theta = this->SampleTheta[static_cast<size_t>(row)];
      while (nextMeridian < this->Meridian.size() && this->Meridian[nextMeridian].Theta < theta)
      {
        winding += this->Meridian[nextMeridian++].Delta;
      }
      while (nextCrossing < this->RowCrossings.size() &&
        this->RowCrossings[nextCrossing].SampleRow < row)
      {
        ++nextCrossing;
      }
      int w = winding;
      double phi = 0.0;
      for (; nextCrossing < this->RowCrossings.size() &&
           this->RowCrossings[nextCrossing].SampleRow == row;
           ++nextCrossing)
      {
        const RowCrossing& crossing = this->RowCrossings[nextCrossing];
        if (w != 0)
        {
          this->PaintSpan(pieceIndex, row, phi, crossing.Phi);
        }
        w += crossing.Delta;
        phi = crossing.Phi;
      }
      if (w != 0)
      {
        this->PaintSpan(pieceIndex, row, phi, TwoPi);
      }
    }
  }

  // --- 4. depth test ---------------------------------------------------------------------------
  void PaintSpan(int32_t pieceIndex, int row, double phiBegin, double phiEnd)
  {
    int first;
    int last;
    this->Grid.SampleColumnsIn(phiBegin, phiEnd, first, last);
    if (first >= last)
    {
      return;
    }
    this->Spans.push_back({ pieceIndex, row, first, last });
    const Piece& piece = this->Pieces[static_cast<size_t>(pieceIndex)];
    for (int column = first; column < last; ++column)
    {
      const std::size_t s = this->Grid.SampleIndex(row, column);
      const int32_t held = this->SamplePiece[s];
      if (held < 0)
      {
        this->Take(s, pieceIndex, piece.DepthLo, piece.DepthHi);
        continue;
      }
      const Piece& other = this->Pieces[static_cast<size_t>(held)];
      // Pieces of one patch on the same side never overlap but along shared edges; a front
      // and a back piece of one patch overlap where it folds, and the nearer must win.
      if ((other.Source == piece.Source && other.Occluder == piece.Occluder) ||
        piece.DepthLo > this->DepthHi[s])
      {
        continue;
      }
      if (piece.DepthHi < this->DepthLo[s])
      {
        this->Take(s, pieceIndex, piece.DepthLo, piece.DepthHi);
        continue;
      }
      // Overlapping depth ranges: compare exact distances along this sample.
      const double mine = this->ExactDepth(pieceIndex, s);
      if (std::isnan(mine))
      {
        continue;
      }
      double theirs =
        this->DepthLo[s] == this->DepthHi[s] ? this->DepthLo[s] : this->ExactDepth(held, s);
      if (std::isnan(theirs) || mine < theirs)
      {
        this->Take(s, pieceIndex, mine, mine);
      }
      else
      {
        this->DepthLo[s] = theirs;
        this->DepthHi[s] = theirs;
      }
    }
  }

  void Take(std::size_t sample, int32_t pieceIndex, double lo, double hi)
  {
    this->SamplePiece[sample] = pieceIndex;
    this->DepthLo[sample] = lo;
    this->DepthHi[sample] = hi;
  }

  /// Exact distance from P_i to the piece along a sample's ray; NaN if the ray does not meet
  /// the piece (up to a margin of 1e-3 of its parameter size). Newton's method starts from the
  /// piece's previous solution (samples are visited row by row, so that is a neighbour's) and,
  /// failing that, from the nearest direction of a 5 x 5 grid over the piece.
  double ExactDepth(int32_t pieceIndex, std::size_t sample)
  {
    Piece& piece = this->Pieces[static_cast<size_t>(pieceIndex)];
    const BezierPatch& patch = this->Patches[static_cast<size_t>(piece.Source)].Geometry;
    const int row = static_cast<int>(sample / static_cast<size_t>(this->Grid.SampleColumns()));
    const int column = static_cast<int>(sample % static_cast<size_t>(this->Grid.SampleColumns()));
    const glm::dvec3 local = this->Grid.SampleDirection(row, column);
    const glm::dvec3 direction = this->Frame.ToWorld(local);
    const UVRect& r = piece.Rect;
    const double marginU = 1e-3 * (r.U1 - r.U0);
    const double marginV = 1e-3 * (r.V1 - r.V0);
    auto solve = [&](double u, double v, double& t)
    {
      t = glm::length(patch.Evaluate(u, v) - this->Frame.Origin);
      if (IntersectRayPatch(patch, this->Frame.Origin, direction, u, v, t) && u >= r.U0 - marginU &&
        u <= r.U1 + marginU && v >= r.V0 - marginV && v <= r.V1 + marginV)
      {
        piece.HasGuess = true;
        piece.GuessU = u;
        piece.GuessV = v;
        return true;
      }
      return false;
    };
    double t;
    if (piece.HasGuess && solve(piece.GuessU, piece.GuessV, t))
    {
      return t;
    }
    double bestDot = -2.0;
    double u = r.CenterU();
    double v = r.CenterV();
    for (int b = 0; b < GuessGrid; ++b)
    {
      for (int a = 0; a < GuessGrid; ++a)
      {
        const double gu = r.U0 + (r.U1 - r.U0) * (a + 0.5) / GuessGrid;
        const double gv = r.V0 + (r.V1 - r.V0) * (b + 0.5) / GuessGrid;
        const double d = glm::dot(this->LocalDirectionTo(patch, gu, gv), local);
        if (d > bestDot)
        {
          bestDot = d;
          u = gu;
          v = gv;
        }
      }
    }
    if (solve(u, v, t))
    {
      return t;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }

  // --- 5. unoccluded projections (paper §4.3 Step 3) ------------------------------------------
  std::vector<std::pair<int32_t, float>> MeasureUnoccluded() const
  {
    std::vector<std::pair<int32_t, float>> result;
    std::vector<size_t> order;
    for (size_t k = 0; k < this->Spans.size(); ++k)
    {
      if (!this->Pieces[static_cast<size_t>(this->Spans[k].PieceIndex)].Occluder)
      {
        order.push_back(k);
      }
    }
    auto sourceOf = [this](size_t k)
    { return this->Pieces[static_cast<size_t>(this->Spans[k].PieceIndex)].Source; };
    std::stable_sort(order.begin(),
      order.end(),
      [&sourceOf](size_t x, size_t y) { return sourceOf(x) < sourceOf(y); });
    // A sample covered by two pieces of one source (along their shared edge) counts once.
    std::vector<int32_t> stamp(this->Grid.SampleCount(), -1);
    const int kt = this->Grid.SamplesTheta();
    const int perCell = this->Grid.SamplesPerCell();
    size_t k = 0;
    while (k < order.size())
    {
      const int32_t source = sourceOf(order[k]);
      double sum = 0.0;
      for (; k < order.size() && sourceOf(order[k]) == source; ++k)
      {
        const Span& span = this->Spans[order[k]];
        const double weight = this->Grid.CellMeasure(span.SampleRow / kt) / perCell;
        for (int column = span.First; column < span.Last; ++column)
        {
          const std::size_t s = this->Grid.SampleIndex(span.SampleRow, column);
          if (stamp[s] != source)
          {
            stamp[s] = source;
            sum += weight;
          }
        }
      }
      result.emplace_back(source, static_cast<float>(sum));
    }
    return result;
  }

  const std::vector<Patch>& Patches;
  const HemisphereGrid& Grid;
  const RBufferFillOptions& Options;
  const std::vector<int32_t>& SurfaceOfPatch;
  std::size_t Receiver;
  HemisphereFrame Frame;
  double SampleSpacing = 0.0;
  double BoundaryTolerance = 0.0;
  double SelfExclusionSquared = 0.0;
  double LowestSampleSine = 0.0;
  std::vector<double> SampleTheta;

  std::vector<Piece> Pieces;
  std::vector<glm::dvec3> Boundary;
  std::vector<RowCrossing> RowCrossings;
  std::vector<MeridianCrossing> Meridian;
  int AxisWinding = 0;
  double ThetaLo = 0.0;
  double ThetaHi = 0.0;
  std::vector<Span> Spans;
  std::vector<int32_t> SamplePiece;
  std::vector<double> DepthLo;
  std::vector<double> DepthHi;
};

} // namespace

ProjectionFiller::ProjectionFiller(const std::vector<Patch>& patches,
  const HemisphereGrid& grid,
  const RBufferFillOptions& options)
  : Patches(patches)
  , Grid(grid)
  , Options(options)
{
  for (const Patch& patch : patches)
  {
    this->SurfaceOfPatch.push_back(patch.SurfaceIndex);
  }
}

void ProjectionFiller::Fill(std::size_t receiver, RBuffer& buffer, CullingStatistics* culling) const
{
  CullingStatistics counts;
  ReceiverProjection projection(
    this->Patches, this->Grid, this->Options, this->SurfaceOfPatch, receiver);
  projection.Run(buffer, counts);
  if (culling)
  {
    *culling += counts;
  }
}

} // namespace sphcover
