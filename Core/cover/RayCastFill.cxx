// SPDX-License-Identifier: BSD-3-Clause
#include "cover/RayCastFill.h"

#include "cover/CandidateCulling.h"
#include "geometry/RayPatchIntersection.h"
#include "subdivision/Patch.h"

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>

namespace sphcover
{

namespace
{
constexpr int MaxQuads = 256;

/// Largest |second partial| bounds of a patch over its domain (convex hull of the nets).
void SecondDerivativeBounds(const BezierPatch& patch, double& uu, double& uv, double& vv)
{
  const int m = patch.DegreeU();
  const int n = patch.DegreeV();
  uu = 0.0;
  uv = 0.0;
  vv = 0.0;
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i + 2 <= m; ++i)
    {
      uu = std::max(uu,
        glm::length(patch.ControlPoint(i + 2, j) - 2.0 * patch.ControlPoint(i + 1, j) +
          patch.ControlPoint(i, j)));
    }
  }
  for (int j = 0; j + 2 <= n; ++j)
  {
    for (int i = 0; i <= m; ++i)
    {
      vv = std::max(vv,
        glm::length(patch.ControlPoint(i, j + 2) - 2.0 * patch.ControlPoint(i, j + 1) +
          patch.ControlPoint(i, j)));
    }
  }
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < m; ++i)
    {
      uv = std::max(uv,
        glm::length(patch.ControlPoint(i + 1, j + 1) - patch.ControlPoint(i + 1, j) -
          patch.ControlPoint(i, j + 1) + patch.ControlPoint(i, j)));
    }
  }
  uu *= m * (m - 1);
  vv *= n * (n - 1);
  uv *= m * n;
}

/// The smallest even (n_u, n_v) whose linear interpolation error bound is within tolerance.
void ChooseResolution(const BezierPatch& patch, double tolerance, int& nu, int& nv)
{
  double uu;
  double uv;
  double vv;
  SecondDerivativeBounds(patch, uu, uv, vv);
  nu = 2;
  nv = 2;
  auto error = [&](int a, int b)
  {
    const double hu = 1.0 / a;
    const double hv = 1.0 / b;
    return (hu * hu * uu + 2.0 * hu * hv * uv + hv * hv * vv) / 8.0;
  };
  while (error(nu, nv) > tolerance && (nu < MaxQuads || nv < MaxQuads))
  {
    // Refine the direction that contributes more.
    const double hu = 1.0 / nu;
    const double hv = 1.0 / nv;
    const double partU = hu * hu * uu + hu * hv * uv;
    const double partV = hv * hv * vv + hu * hv * uv;
    if ((partU >= partV && nu < MaxQuads) || nv >= MaxQuads)
    {
      nu = std::min(MaxQuads, nu + std::max(2, (nu / 8) * 2));
    }
    else
    {
      nv = std::min(MaxQuads, nv + std::max(2, (nv / 8) * 2));
    }
  }
}

/// An Embree ray from `origin` along `direction` (single precision, as Embree takes them),
/// starting at `tNear`, with no hit yet.
RTCRayHit MakeRayHit(const glm::dvec3& origin, const glm::dvec3& direction, float tNear = 0.0f)
{
  RTCRayHit rayHit;
  rayHit.ray.org_x = static_cast<float>(origin.x);
  rayHit.ray.org_y = static_cast<float>(origin.y);
  rayHit.ray.org_z = static_cast<float>(origin.z);
  rayHit.ray.dir_x = static_cast<float>(direction.x);
  rayHit.ray.dir_y = static_cast<float>(direction.y);
  rayHit.ray.dir_z = static_cast<float>(direction.z);
  rayHit.ray.tnear = tNear;
  rayHit.ray.tfar = std::numeric_limits<float>::infinity();
  rayHit.ray.time = 0.0f;
  rayHit.ray.mask = 0xFFFFFFFFu;
  rayHit.ray.id = 0;
  rayHit.ray.flags = 0;
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rayHit;
}

/// Per-sample hit parameters of one receiver.
struct HitScratch
{
  std::vector<double> U;
  std::vector<double> V;
  std::vector<float> T;
};

/// The intersect context handed to Embree, extended with what the filter needs.
struct ReceiverContext
{
  RTCIntersectContext Context;
  unsigned int Receiver;
  float SelfExclusion;
  bool CountSelf;
  bool BackFacesOcclude;
};

void FilterHit(const RTCFilterFunctionNArguments* args)
{
  const ReceiverContext* context = reinterpret_cast<const ReceiverContext*>(args->context);
  for (unsigned int k = 0; k < args->N; ++k)
  {
    if (args->valid[k] == 0)
    {
      continue;
    }
    const float dot = RTCHitN_Ng_x(args->hit, args->N, k) * RTCRayN_dir_x(args->ray, args->N, k) +
      RTCHitN_Ng_y(args->hit, args->N, k) * RTCRayN_dir_y(args->ray, args->N, k) +
      RTCHitN_Ng_z(args->hit, args->N, k) * RTCRayN_dir_z(args->ray, args->N, k);
    // Embree's Ng is cross(v1 - v0, v2 - v0); the triangles are wound like dQ/du x dQ/dv, so a
    // front-side hit has Ng . dir < 0. Back sides are skipped unless they occlude.
    if (!(dot < 0.0f) && !context->BackFacesOcclude)
    {
      args->valid[k] = 0;
      continue;
    }
    if (RTCHitN_geomID(args->hit, args->N, k) == context->Receiver &&
      (!context->CountSelf || RTCRayN_tfar(args->ray, args->N, k) < context->SelfExclusion))
    {
      args->valid[k] = 0;
    }
  }
}
}

std::string RayCastCoordinateProblem(const std::vector<Patch>& patches)
{
  for (size_t p = 0; p < patches.size(); ++p)
  {
    for (const glm::dvec3& point : patches[p].Geometry.ControlPoints())
    {
      if (!(LargestCoordinate({ point }) <= MaxRayCastCoordinate))
      {
        std::ostringstream problem;
        problem << "patch " << p << " (surface " << patches[p].SurfaceIndex
                << ") has a control point at " << point.x << ", " << point.y << ", " << point.z
                << ", beyond the coordinates ray casting (Embree) can trace (|x| <= "
                << MaxRayCastCoordinate << ")";
        return problem.str();
      }
    }
  }
  return std::string();
}

struct RayCastFiller::Implementation
{
  const std::vector<Patch>& Patches;
  const HemisphereGrid& Grid;
  RBufferFillOptions Options;
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;
  std::vector<int32_t> SurfaceOfPatch;
  std::vector<int> QuadsU;
  std::vector<int> QuadsV;
  std::size_t Triangles = 0;

  Implementation(const std::vector<Patch>& patches,
    const HemisphereGrid& grid,
    const RBufferFillOptions& options)
    : Patches(patches)
    , Grid(grid)
    , Options(options)
  {
    // Every stage that casts rays (the ray fill, the refinement's probes, the renderer) comes
    // through here, whatever dataset the VTK filters were given: refuse what Embree aborts on.
    const std::string problem = RayCastCoordinateProblem(patches);
    if (!problem.empty())
    {
      throw std::invalid_argument(problem);
    }
    this->Device = rtcNewDevice("threads=1");
    if (!this->Device)
    {
      throw std::runtime_error("RayCastFiller: Embree could not create a device (error " +
        std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
    }
    this->Scene = rtcNewScene(this->Device);
    rtcSetSceneFlags(this->Scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION | RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(this->Scene, RTC_BUILD_QUALITY_HIGH);
    for (const Patch& patch : patches)
    {
      this->SurfaceOfPatch.push_back(patch.SurfaceIndex);
    }
    this->ChooseResolutions();
    for (size_t p = 0; p < patches.size(); ++p)
    {
      this->AddPatch(p);
    }
    rtcCommitScene(this->Scene);
    const RTCError error = rtcGetDeviceError(this->Device);
    if (error != RTC_ERROR_NONE)
    {
      this->Release();
      throw std::runtime_error(
        "RayCastFiller: Embree failed to build the scene (error " + std::to_string(error) + ")");
    }
  }

  ~Implementation() { this->Release(); }

  void Release()
  {
    if (this->Scene)
    {
      rtcReleaseScene(this->Scene);
      this->Scene = nullptr;
    }
    if (this->Device)
    {
      rtcReleaseDevice(this->Device);
      this->Device = nullptr;
    }
  }

  void ChooseResolutions()
  {
    const size_t count = this->Patches.size();
    this->QuadsU.resize(count);
    this->QuadsV.resize(count);
    // Largest resolution per (surface, degrees), so that uniformly split surfaces match.
    std::map<std::tuple<int, int, int>, std::pair<int, int>> largest;
    for (size_t p = 0; p < count; ++p)
    {
      const BezierPatch& geometry = this->Patches[p].Geometry;
      ChooseResolution(geometry,
        this->Options.TessellationTolerance * geometry.Size(),
        this->QuadsU[p],
        this->QuadsV[p]);
      auto& entry = largest[std::make_tuple(
        this->Patches[p].SurfaceIndex, geometry.DegreeU(), geometry.DegreeV())];
      entry.first = std::max(entry.first, this->QuadsU[p]);
      entry.second = std::max(entry.second, this->QuadsV[p]);
    }
    for (size_t p = 0; p < count; ++p)
    {
      const BezierPatch& geometry = this->Patches[p].Geometry;
      const auto& entry = largest[std::make_tuple(
        this->Patches[p].SurfaceIndex, geometry.DegreeU(), geometry.DegreeV())];
      this->QuadsU[p] = entry.first;
      this->QuadsV[p] = entry.second;
    }
  }

  void AddPatch(size_t p)
  {
    const BezierPatch& patch = this->Patches[p].Geometry;
    const int nu = this->QuadsU[p];
    const int nv = this->QuadsV[p];
    RTCGeometry geometry = rtcNewGeometry(this->Device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const size_t vertexCount = static_cast<size_t>((nu + 1) * (nv + 1));
    float* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
    for (int j = 0; j <= nv; ++j)
    {
      for (int i = 0; i <= nu; ++i)
      {
        // Exact parameters at the ends so that neighbours evaluate the same boundary points.
        const double u = i == nu ? 1.0 : static_cast<double>(i) / nu;
        const double v = j == nv ? 1.0 : static_cast<double>(j) / nv;
        const glm::dvec3 q = patch.Evaluate(u, v);
        float* out = vertices + 3 * static_cast<size_t>(j * (nu + 1) + i);
        out[0] = static_cast<float>(q.x);
        out[1] = static_cast<float>(q.y);
        out[2] = static_cast<float>(q.z);
      }
    }
    const size_t triangleCount = static_cast<size_t>(2 * nu * nv);
    unsigned int* indices = static_cast<unsigned int*>(rtcSetNewGeometryBuffer(geometry,
      RTC_BUFFER_TYPE_INDEX,
      0,
      RTC_FORMAT_UINT3,
      3 * sizeof(unsigned int),
      triangleCount));
    for (int j = 0; j < nv; ++j)
    {
      for (int i = 0; i < nu; ++i)
      {
        const unsigned int v00 = static_cast<unsigned int>(j * (nu + 1) + i);
        const unsigned int v10 = v00 + 1;
        const unsigned int v01 = v00 + static_cast<unsigned int>(nu + 1);
        const unsigned int v11 = v01 + 1;
        unsigned int* t = indices + 6 * static_cast<size_t>(j * nu + i);
        // Counter-clockwise in (u, v), so cross(v1 - v0, v2 - v0) points like dQ/du x dQ/dv.
        t[0] = v00;
        t[1] = v10;
        t[2] = v11;
        t[3] = v00;
        t[4] = v11;
        t[5] = v01;
      }
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(this->Scene, geometry, static_cast<unsigned int>(p));
    rtcReleaseGeometry(geometry);
    this->Triangles += triangleCount;
  }

  /// Patch parameters of a hit from its triangle and barycentric coordinates.
  void HitParameters(size_t p, unsigned int primitive, float b1, float b2, double& u, double& v)
    const
  {
    const int nu = this->QuadsU[p];
    const int nv = this->QuadsV[p];
    const int quad = static_cast<int>(primitive / 2);
    const int i = quad % nu;
    const int j = quad / nu;
    if (primitive % 2 == 0)
    {
      u = (i + b1 + b2) / nu;
      v = (j + b2) / static_cast<double>(nv);
    }
    else
    {
      u = (i + b1) / static_cast<double>(nu);
      v = (j + b1 + b2) / nv;
    }
  }
};

RayCastFiller::RayCastFiller(const std::vector<Patch>& patches,
  const HemisphereGrid& grid,
  const RBufferFillOptions& options)
  : Impl(std::make_unique<Implementation>(patches, grid, options))
{
}

RayCastFiller::~RayCastFiller() = default;

bool RayCastFiller::CastRay(const glm::dvec3& origin,
  const glm::dvec3& direction,
  RayHit& hit) const
{
  const Implementation& impl = *this->Impl;
  ReceiverContext context;
  rtcInitIntersectContext(&context.Context);
  context.Context.filter = FilterHit;
  // No receiver patch: nothing is excluded, and back sides are hits (opaque surfaces).
  context.Receiver = RTC_INVALID_GEOMETRY_ID;
  context.SelfExclusion = 0.0f;
  context.CountSelf = true;
  context.BackFacesOcclude = true;
  RTCRayHit rayHit = MakeRayHit(origin, direction);
  rtcIntersect1(impl.Scene, &context.Context, &rayHit);
  if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
  {
    return false;
  }
  hit.Patch = rayHit.hit.geomID;
  impl.HitParameters(hit.Patch, rayHit.hit.primID, rayHit.hit.u, rayHit.hit.v, hit.U, hit.V);
  hit.T = rayHit.ray.tfar;
  const BezierPatch& geometry = impl.Patches[hit.Patch].Geometry;
  if (impl.Options.RefineHits)
  {
    double u = hit.U;
    double v = hit.V;
    double t = hit.T;
    // Accept the refinement only where it stays on the patch near the triangle's point.
    constexpr double margin = 1e-3;
    if (IntersectRayPatch(geometry, origin, direction, u, v, t) && u >= -margin &&
      u <= 1.0 + margin && v >= -margin && v <= 1.0 + margin)
    {
      hit.U = std::clamp(u, 0.0, 1.0);
      hit.V = std::clamp(v, 0.0, 1.0);
      hit.T = t;
    }
  }
  glm::dvec3 q;
  glm::dvec3 qu;
  glm::dvec3 qv;
  EvaluatePointAndPartials(geometry, hit.U, hit.V, q, qu, qv);
  glm::dvec3 normal = glm::cross(qu, qv);
  if (!(glm::length(normal) > 0.0))
  {
    normal = glm::dvec3(rayHit.hit.Ng_x, rayHit.hit.Ng_y, rayHit.hit.Ng_z);
  }
  hit.FrontSide = glm::dot(normal, direction) < 0.0;
  return true;
}

std::size_t RayCastFiller::TriangleCount() const
{
  return this->Impl->Triangles;
}

void RayCastFiller::Resolution(std::size_t patch, int& quadsU, int& quadsV) const
{
  quadsU = this->Impl->QuadsU[patch];
  quadsV = this->Impl->QuadsV[patch];
}

std::size_t RayCastFiller::EnvironmentBytes() const
{
  // Vertices and indices (12 bytes each per vertex / triangle, about one vertex per two
  // triangles) plus Embree's high-quality BVH, about 40 bytes per triangle (its reference
  // figures: node and triangle storage of the 4-wide BVH with spatial splits).
  return this->Impl->Triangles * (6 + 12 + 40);
}

void RayCastFiller::Fill(std::size_t receiver, RBuffer& buffer, CullingStatistics*) const
{
  const Implementation& impl = *this->Impl;
  const HemisphereGrid& grid = impl.Grid;
  const Patch& patch = impl.Patches[receiver];
  const HemisphereFrame frame = HemisphereFrame::OfPatch(patch);
  buffer.Reset(receiver);

  ReceiverContext context;
  rtcInitIntersectContext(&context.Context);
  context.Context.filter = FilterHit;
  // Rays from one point in neighbouring directions: coherent.
  context.Context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  context.Receiver = static_cast<unsigned int>(receiver);
  context.SelfExclusion =
    static_cast<float>(impl.Options.SelfExclusionFraction * patch.Geometry.Size());
  context.CountSelf = impl.Options.CountSelfVisibility;
  context.BackFacesOcclude = impl.Options.BackFacesOcclude;

  // Per-sample hit parameters for the lazy refinement, reused by each thread.
  thread_local HitScratch scratch;
  scratch.U.resize(grid.SampleCount());
  scratch.V.resize(grid.SampleCount());
  scratch.T.resize(grid.SampleCount());

  for (int row = 0; row < grid.SampleRows(); ++row)
  {
    for (int column = 0; column < grid.SampleColumns(); ++column)
    {
      const glm::dvec3 direction = frame.ToWorld(grid.SampleDirection(row, column));
      RTCRayHit rayHit = MakeRayHit(frame.Origin, direction);
      rtcIntersect1(impl.Scene, &context.Context, &rayHit);
      if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      {
        continue;
      }
      if (!(rayHit.hit.Ng_x * rayHit.ray.dir_x + rayHit.hit.Ng_y * rayHit.ray.dir_y +
              rayHit.hit.Ng_z * rayHit.ray.dir_z <
            0.0f))
      {
        continue; // a back side: it hides what is behind it, the sample stays empty
      }
      const size_t source = rayHit.hit.geomID;
      const BezierPatch& geometry = impl.Patches[source].Geometry;
      const std::size_t sample = grid.SampleIndex(row, column);
      double u;
      double v;
      impl.HitParameters(source, rayHit.hit.primID, rayHit.hit.u, rayHit.hit.v, u, v);
      // The exact normal at the hit's parameters decides grazing (a triangle's normal can be
      // off by several degrees on a curved patch).
      glm::dvec3 q;
      glm::dvec3 qu;
      glm::dvec3 qv;
      EvaluatePointAndPartials(geometry, u, v, q, qu, qv);
      glm::dvec3 normal = glm::cross(qu, qv);
      if (!(glm::length(normal) > 0.0))
      {
        normal = glm::dvec3(rayHit.hit.Ng_x, rayHit.hit.Ng_y, rayHit.hit.Ng_z);
      }
      const double cosine =
        std::fabs(glm::dot(normal, direction)) / std::max(glm::length(normal), 1e-300);
      scratch.U[sample] = u;
      scratch.V[sample] = v;
      scratch.T[sample] = rayHit.ray.tfar;
      // With refinement the exact R is computed for the cells' representative samples only
      // (in Classify); the other samples' R is never used.
      buffer.SetSample(sample,
        static_cast<int32_t>(source),
        impl.Options.RefineHits ? std::numeric_limits<float>::quiet_NaN() : rayHit.ray.tfar,
        cosine < impl.Options.GrazingCosine);
    }
  }
  buffer.Classify(
    [&](std::size_t sample, int32_t source) -> float
    {
      const BezierPatch& geometry = impl.Patches[static_cast<size_t>(source)].Geometry;
      const int row = static_cast<int>(sample / static_cast<size_t>(grid.SampleColumns()));
      const int column = static_cast<int>(sample % static_cast<size_t>(grid.SampleColumns()));
      const glm::dvec3 direction = frame.ToWorld(grid.SampleDirection(row, column));
      double u = scratch.U[sample];
      double v = scratch.V[sample];
      double t = scratch.T[sample];
      // Accept the refinement only where it stays on the patch near the triangle's point.
      constexpr double margin = 1e-3;
      if (IntersectRayPatch(geometry, frame.Origin, direction, u, v, t) && u >= -margin &&
        u <= 1.0 + margin && v >= -margin && v <= 1.0 + margin)
      {
        return static_cast<float>(t);
      }
      return static_cast<float>(scratch.T[sample]);
    },
    &impl.SurfaceOfPatch,
    impl.Options.DiffuseRounding);
}

bool RayCastFiller::FirstHit(const glm::dvec3& origin,
  const glm::dvec3& direction,
  double tNear,
  std::size_t& patch,
  double& distance,
  bool& front) const
{
  ReceiverContext context;
  rtcInitIntersectContext(&context.Context);
  context.Context.filter = FilterHit;
  context.Receiver = RTC_INVALID_GEOMETRY_ID;
  context.SelfExclusion = 0.0f;
  context.CountSelf = true;
  context.BackFacesOcclude = true; // every side counts: the caller asks which one it met
  RTCRayHit rayHit = MakeRayHit(origin, direction, static_cast<float>(tNear));
  rtcIntersect1(this->Impl->Scene, &context.Context, &rayHit);
  if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
  {
    return false;
  }
  patch = rayHit.hit.geomID;
  distance = rayHit.ray.tfar;
  front = rayHit.hit.Ng_x * rayHit.ray.dir_x + rayHit.hit.Ng_y * rayHit.ray.dir_y +
      rayHit.hit.Ng_z * rayHit.ray.dir_z <
    0.0f;
  return true;
}

} // namespace sphcover
