// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/RayCaster.h"

#include "geometry/BoundingBoxTree.h"
#include "geometry/RayPatchIntersection.h"

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
#include <utility>

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

/// Whether the patch is exactly a convex planar quadrilateral: its corners lie in one plane,
/// make a convex quadrilateral, and every control point is the bilinear interpolation of the
/// corners at its Greville parameters (i / m, j / n), i.e. the patch is a bilinear one,
/// degree-elevated or not. Its two triangles are then the patch itself, not an approximation.
bool IsConvexPlanarQuad(const BezierPatch& patch)
{
  const int m = patch.DegreeU();
  const int n = patch.DegreeV();
  const glm::dvec3 a = patch.ControlPoint(0, 0);
  const glm::dvec3 b = patch.ControlPoint(m, 0);
  const glm::dvec3 c = patch.ControlPoint(m, n);
  const glm::dvec3 d = patch.ControlPoint(0, n);
  // Rounding of the subdivision's de Casteljau steps only: far below any tessellation tolerance.
  const double tolerance = 1e-9 * patch.Size();
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= m; ++i)
    {
      const double s = static_cast<double>(i) / m;
      const double t = static_cast<double>(j) / n;
      const glm::dvec3 bilinear = (1.0 - t) * ((1.0 - s) * a + s * b) + t * ((1.0 - s) * d + s * c);
      if (!(glm::length(patch.ControlPoint(i, j) - bilinear) <= tolerance))
      {
        return false;
      }
    }
  }
  const glm::dvec3 normal = glm::cross(b - a, d - a);
  const double length = glm::length(normal);
  if (!(length > 0.0) || !(std::fabs(glm::dot(c - a, normal / length)) <= tolerance))
  {
    return false;
  }
  // Convex: every corner turns the same way about the normal.
  return glm::dot(glm::cross(b - a, c - b), normal) > 0.0 &&
    glm::dot(glm::cross(c - b, d - c), normal) > 0.0 &&
    glm::dot(glm::cross(d - c, a - d), normal) > 0.0 &&
    glm::dot(glm::cross(a - d, b - a), normal) > 0.0;
}

/// (1, 1) for a convex planar quadrilateral (IsConvexPlanarQuad); otherwise the smallest even
/// (n_u, n_v) whose linear interpolation error bound is within tolerance: over a cell
/// h_u x h_v it is (h_u^2 M_uu + 2 h_u h_v M_uv + h_v^2 M_vv) / 8.
void ChooseResolution(const BezierPatch& patch, double tolerance, int& nu, int& nv)
{
  if (IsConvexPlanarQuad(patch))
  {
    // Two triangles are exact, and the characteristic point lies in their plane, so it needs
    // not be a vertex.
    nu = 1;
    nv = 1;
    return;
  }
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
RTCRayHit MakeRayHit(const glm::dvec3& origin, const glm::dvec3& direction, float tNear)
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

/// Whether a ray's hit is on its triangle's front side: Embree's Ng is cross(v1 - v0, v2 - v0),
/// the triangles are wound like dQ/du x dQ/dv, so a front-side hit has Ng . dir < 0.
bool FrontSide(const RTCRayHit& rayHit)
{
  return rayHit.hit.Ng_x * rayHit.ray.dir_x + rayHit.hit.Ng_y * rayHit.ray.dir_y +
    rayHit.hit.Ng_z * rayHit.ray.dir_z <
    0.0f;
}

bool FrontSide(const RTCRayHit16& packet, int k)
{
  return packet.hit.Ng_x[k] * packet.ray.dir_x[k] + packet.hit.Ng_y[k] * packet.ray.dir_y[k] +
    packet.hit.Ng_z[k] * packet.ray.dir_z[k] <
    0.0f;
}

/// The intersect context handed to Embree, extended with the caller's filter.
struct FilterContext
{
  RTCIntersectContext Context;
  RayFilter Filter;
};

/// Embree's context filter: asks the caller's predicate about every candidate hit. Installed
/// only for queries that filter during traversal (RayFilter::RejectsAllNearer): a callback per
/// candidate hit costs about a tenth of a row's rays (Documentation/notes/ray-casting.md).
void FilterHit(const RTCFilterFunctionNArguments* args)
{
  const RayFilter& filter = reinterpret_cast<const FilterContext*>(args->context)->Filter;
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
    // front-side hit has Ng . dir < 0.
    if (!filter.Accept(filter.Context,
          RTCHitN_geomID(args->hit, args->N, k),
          RTCRayN_tfar(args->ray, args->N, k),
          dot < 0.0f))
    {
      args->valid[k] = 0;
    }
  }
}

/// Sets up the context of a query with `filter` from `tNear` and returns where its rays start:
/// the filter during traversal, or, when the caller promises RayFilter::RejectsAllNearer, no
/// filter from that distance on (`firstHitOnly`: the filter is then asked about the first hit).
float PrepareQuery(const RayFilter& filter,
  float tNear,
  bool coherent,
  FilterContext& context,
  bool& firstHitOnly)
{
  firstHitOnly = filter.Accept && filter.RejectsAllNearer > 0.0f;
  rtcInitIntersectContext(&context.Context);
  context.Context.filter = filter.Accept && !firstHitOnly ? FilterHit : nullptr;
  if (coherent)
  {
    context.Context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  }
  context.Filter = filter;
  return firstHitOnly ? std::max(tNear, filter.RejectsAllNearer) : tNear;
}
}

std::string RayCastCoordinateProblem(const std::vector<RayCastPatch>& patches)
{
  for (size_t p = 0; p < patches.size(); ++p)
  {
    if (!patches[p].Geometry)
    {
      continue;
    }
    for (const glm::dvec3& point : patches[p].Geometry->ControlPoints())
    {
      if (!(LargestCoordinate({ point }) <= MaxRayCastCoordinate))
      {
        std::ostringstream problem;
        problem << "patch " << p << " (surface " << patches[p].Surface
                << ") has a control point at " << point.x << ", " << point.y << ", " << point.z
                << ", beyond the coordinates ray casting (Embree) can trace (|x| <= "
                << MaxRayCastCoordinate << ")";
        return problem.str();
      }
    }
  }
  return std::string();
}

struct RayCaster::Implementation
{
  std::vector<RayCastPatch> Patches;
  RayCasterOptions Options;
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;
  std::vector<int> QuadsU;
  std::vector<int> QuadsV;
  std::size_t Triangles = 0;
  std::size_t Vertices = 0;
  /// Per patch the bounding box of its triangles, and a tree over them (PatchesNear).
  std::vector<Box> TriangleBounds;
  std::unique_ptr<BoundingBoxTree> BoundsTree;

  Implementation(std::vector<RayCastPatch> patches, const RayCasterOptions& options)
    : Patches(std::move(patches))
    , Options(options)
  {
    for (size_t p = 0; p < this->Patches.size(); ++p)
    {
      if (!this->Patches[p].Geometry)
      {
        throw std::invalid_argument("RayCaster: patch " + std::to_string(p) + " has no geometry");
      }
    }
    // Every stage that casts rays (the ray fill, the refinement's probes, the renderer) comes
    // through here, whatever dataset the VTK filters were given: refuse what Embree aborts on.
    const std::string problem = RayCastCoordinateProblem(this->Patches);
    if (!problem.empty())
    {
      throw std::invalid_argument(problem);
    }
    // One thread for the BVH build: the environment is built once, and the result must not
    // depend on a thread count.
    this->Device = rtcNewDevice("threads=1");
    if (!this->Device)
    {
      throw std::runtime_error("RayCaster: Embree could not create a device (error " +
        std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
    }
    this->Scene = rtcNewScene(this->Device);
    rtcSetSceneFlags(this->Scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION | RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(this->Scene, RTC_BUILD_QUALITY_HIGH);
    this->ChooseResolutions();
    this->TriangleBounds.resize(this->Patches.size());
    for (size_t p = 0; p < this->Patches.size(); ++p)
    {
      this->AddPatch(p);
    }
    this->BoundsTree = std::make_unique<BoundingBoxTree>(this->TriangleBounds);
    rtcCommitScene(this->Scene);
    const RTCError error = rtcGetDeviceError(this->Device);
    if (error != RTC_ERROR_NONE)
    {
      this->Release();
      throw std::runtime_error(
        "RayCaster: Embree failed to build the scene (error " + std::to_string(error) + ")");
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
      const BezierPatch& geometry = *this->Patches[p].Geometry;
      ChooseResolution(geometry,
        this->Options.TessellationTolerance * geometry.Size(),
        this->QuadsU[p],
        this->QuadsV[p]);
      auto& entry = largest[std::make_tuple(
        static_cast<int>(this->Patches[p].Surface), geometry.DegreeU(), geometry.DegreeV())];
      entry.first = std::max(entry.first, this->QuadsU[p]);
      entry.second = std::max(entry.second, this->QuadsV[p]);
    }
    for (size_t p = 0; p < count; ++p)
    {
      const BezierPatch& geometry = *this->Patches[p].Geometry;
      const auto& entry = largest[std::make_tuple(
        static_cast<int>(this->Patches[p].Surface), geometry.DegreeU(), geometry.DegreeV())];
      this->QuadsU[p] = entry.first;
      this->QuadsV[p] = entry.second;
    }
  }

  void AddPatch(size_t p)
  {
    const BezierPatch& patch = *this->Patches[p].Geometry;
    const int nu = this->QuadsU[p];
    const int nv = this->QuadsV[p];
    RTCGeometry geometry = rtcNewGeometry(this->Device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const size_t vertexCount = static_cast<size_t>((nu + 1) * (nv + 1));
    float* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
    Box& bounds = this->TriangleBounds[p];
    bounds.Lower = glm::dvec3(std::numeric_limits<double>::infinity());
    bounds.Upper = -bounds.Lower;
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
        const glm::dvec3 vertex(out[0], out[1], out[2]);
        bounds.Lower = glm::min(bounds.Lower, vertex);
        bounds.Upper = glm::max(bounds.Upper, vertex);
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
    this->Vertices += vertexCount;
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

RayCaster::RayCaster(std::vector<RayCastPatch> patches, const RayCasterOptions& options)
  : Impl(std::make_unique<Implementation>(std::move(patches), options))
{
}

RayCaster::~RayCaster() = default;

bool RayCaster::Intersect(const glm::dvec3& origin,
  const glm::dvec3& direction,
  float tNear,
  const RayFilter& filter,
  bool coherent,
  TriangleHit& hit) const
{
  const Implementation& impl = *this->Impl;
  FilterContext context;
  bool firstHitOnly;
  const float start = PrepareQuery(filter, tNear, coherent, context, firstHitOnly);
  RTCRayHit rayHit = MakeRayHit(origin, direction, start);
  rtcIntersect1(impl.Scene, &context.Context, &rayHit);
  if (firstHitOnly && rayHit.hit.geomID != RTC_INVALID_GEOMETRY_ID &&
    !filter.Accept(filter.Context, rayHit.hit.geomID, rayHit.ray.tfar, FrontSide(rayHit)))
  {
    // Rare: the first hit is one the rays pass (a pane's back side): again, filtered throughout.
    context.Context.filter = FilterHit;
    rayHit = MakeRayHit(origin, direction, start);
    rtcIntersect1(impl.Scene, &context.Context, &rayHit);
  }
  if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
  {
    return false;
  }
  hit.Patch = rayHit.hit.geomID;
  impl.HitParameters(hit.Patch, rayHit.hit.primID, rayHit.hit.u, rayHit.hit.v, hit.U, hit.V);
  hit.Distance = rayHit.ray.tfar;
  hit.FrontSide = FrontSide(rayHit);
  hit.TriangleNormal = glm::dvec3(rayHit.hit.Ng_x, rayHit.hit.Ng_y, rayHit.hit.Ng_z);
  return true;
}

void RayCaster::IntersectPacket(const glm::dvec3& origin,
  const glm::dvec3* directions,
  int count,
  float tNear,
  const RayFilter& filter,
  TriangleHit* hits,
  bool* found) const
{
  const Implementation& impl = *this->Impl;
  FilterContext context;
  bool firstHitOnly;
  const float start = PrepareQuery(filter, tNear, true, context, firstHitOnly);
  alignas(64) int valid[PacketSize];
  alignas(64) RTCRayHit16 packet;
  const float ox = static_cast<float>(origin.x);
  const float oy = static_cast<float>(origin.y);
  const float oz = static_cast<float>(origin.z);
  for (int k = 0; k < PacketSize; ++k)
  {
    const bool active = k < count;
    valid[k] = active ? -1 : 0;
    // Inactive lanes get a copy of the first ray: finite data, never traced.
    const glm::dvec3& direction = directions[active ? k : 0];
    packet.ray.org_x[k] = ox;
    packet.ray.org_y[k] = oy;
    packet.ray.org_z[k] = oz;
    packet.ray.dir_x[k] = static_cast<float>(direction.x);
    packet.ray.dir_y[k] = static_cast<float>(direction.y);
    packet.ray.dir_z[k] = static_cast<float>(direction.z);
    packet.ray.tnear[k] = start;
    packet.ray.tfar[k] = std::numeric_limits<float>::infinity();
    packet.ray.time[k] = 0.0f;
    packet.ray.mask[k] = 0xFFFFFFFFu;
    packet.ray.id[k] = static_cast<unsigned int>(k);
    packet.ray.flags[k] = 0;
    packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, impl.Scene, &context.Context, &packet);
  if (firstHitOnly)
  {
    // The rays whose first hit the filter rejects (rare: a pane's back side), again, filtered
    // throughout; the others keep their hits.
    bool again = false;
    for (int k = 0; k < count; ++k)
    {
      valid[k] = packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID &&
          !filter.Accept(
            filter.Context, packet.hit.geomID[k], packet.ray.tfar[k], FrontSide(packet, k))
        ? -1
        : 0;
      if (valid[k] != 0)
      {
        again = true;
        packet.ray.tfar[k] = std::numeric_limits<float>::infinity();
        packet.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        packet.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
      }
    }
    if (again)
    {
      context.Context.filter = FilterHit;
      rtcIntersect16(valid, impl.Scene, &context.Context, &packet);
    }
  }
  for (int k = 0; k < count; ++k)
  {
    found[k] = packet.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID;
    if (!found[k])
    {
      continue;
    }
    TriangleHit& hit = hits[k];
    hit.Patch = packet.hit.geomID[k];
    impl.HitParameters(
      hit.Patch, packet.hit.primID[k], packet.hit.u[k], packet.hit.v[k], hit.U, hit.V);
    hit.Distance = packet.ray.tfar[k];
    hit.FrontSide = FrontSide(packet, k);
    hit.TriangleNormal = glm::dvec3(packet.hit.Ng_x[k], packet.hit.Ng_y[k], packet.hit.Ng_z[k]);
  }
}

bool RayCaster::Refine(std::size_t patch,
  const glm::dvec3& origin,
  const glm::dvec3& direction,
  double& u,
  double& v,
  double& t) const
{
  double refinedU = u;
  double refinedV = v;
  double refinedT = t;
  // Accept the refinement only where it stays on the patch near the triangle's point.
  constexpr double margin = 1e-3;
  if (IntersectRayPatch(
        *this->Impl->Patches[patch].Geometry, origin, direction, refinedU, refinedV, refinedT) &&
    refinedU >= -margin && refinedU <= 1.0 + margin && refinedV >= -margin &&
    refinedV <= 1.0 + margin)
  {
    u = refinedU;
    v = refinedV;
    t = refinedT;
    return true;
  }
  return false;
}

bool RayCaster::CastRay(const glm::dvec3& origin,
  const glm::dvec3& direction,
  float tNear,
  const RayFilter& filter,
  RayHit& hit) const
{
  // Without a filter nothing is excluded, and back sides are hits (opaque surfaces).
  TriangleHit triangle;
  if (!this->Intersect(origin, direction, tNear, filter, false, triangle))
  {
    return false;
  }
  this->ResolveHit(origin, direction, triangle, hit, false);
  return true;
}

void RayCaster::CastPacket(const glm::dvec3& origin,
  const glm::dvec3* directions,
  int count,
  float tNear,
  const RayFilter& filter,
  RayHit* hits,
  bool* found,
  bool quadStart) const
{
  TriangleHit triangles[PacketSize];
  this->IntersectPacket(origin, directions, count, tNear, filter, triangles, found);
  for (int k = 0; k < count; ++k)
  {
    if (found[k])
    {
      this->ResolveHit(origin, directions[k], triangles[k], hits[k], quadStart);
    }
  }
}

namespace
{
/// The (u, v, t) where the ray meets a convex planar bilinear patch with corners a = Q(0, 0),
/// b = Q(1, 0), c = Q(1, 1), d = Q(0, 1), in closed form: t on the plane, then (u, v) of the
/// bilinear map's inverse in the plane's two dominant coordinates (Q = a + e u + f v + g u v:
/// v the root in [0, 1] of k2 v^2 + k1 v + k0 = 0 of the cross products). False where the ray
/// is parallel to the plane or no root lies in the patch (the caller then starts from the
/// triangle's point).
bool QuadIntersection(const glm::dvec3& a,
  const glm::dvec3& b,
  const glm::dvec3& c,
  const glm::dvec3& d,
  const glm::dvec3& origin,
  const glm::dvec3& direction,
  double& u,
  double& v,
  double& t)
{
  const glm::dvec3 normal = glm::cross(b - a, d - a) + glm::cross(c - b, c - d);
  const double facing = glm::dot(direction, normal);
  if (!(std::fabs(facing) > 0.0))
  {
    return false;
  }
  t = glm::dot(a - origin, normal) / facing;
  const glm::dvec3 point = origin + t * direction;
  // The plane's two coordinates in which the quad's projection is largest.
  const glm::dvec3 magnitude = glm::abs(normal);
  const int drop = magnitude.x >= magnitude.y && magnitude.x >= magnitude.z ? 0
    : magnitude.y >= magnitude.z                                            ? 1
                                                                            : 2;
  const int i = drop == 0 ? 1 : 0;
  const int j = drop == 2 ? 1 : 2;
  auto cross2 = [i, j](const glm::dvec3& x, const glm::dvec3& y)
  { return x[i] * y[j] - x[j] * y[i]; };
  const glm::dvec3 e = b - a;
  const glm::dvec3 f = d - a;
  const glm::dvec3 g = a - b + c - d;
  const glm::dvec3 h = point - a;
  const double k2 = cross2(g, f);
  const double k1 = cross2(e, f) + cross2(h, g);
  const double k0 = cross2(h, e);
  const double scale = std::fabs(cross2(e, f));
  double roots[2];
  int count = 0;
  if (std::fabs(k2) <= 1e-12 * scale)
  {
    // A parallelogram (or nearly): the equation is linear.
    if (!(std::fabs(k1) > 0.0))
    {
      return false;
    }
    roots[count++] = -k0 / k1;
  }
  else
  {
    const double discriminant = k1 * k1 - 4.0 * k0 * k2;
    if (!(discriminant >= 0.0))
    {
      return false;
    }
    const double w = std::sqrt(discriminant);
    // Without the cancellation of -k1 + w: q = -(k1 + sign(k1) w) / 2, roots q / k2 and k0 / q.
    const double q = -0.5 * (k1 + std::copysign(w, k1));
    roots[count++] = q / k2;
    if (q != 0.0)
    {
      roots[count++] = k0 / q;
    }
  }
  constexpr double slack = 1e-6;
  for (int r = 0; r < count; ++r)
  {
    const double root = roots[r];
    if (!(root >= -slack && root <= 1.0 + slack))
    {
      continue;
    }
    // h - f v = (e + g v) u: u by least squares over the three coordinates.
    const glm::dvec3 along = e + g * root;
    const double length2 = glm::dot(along, along);
    if (!(length2 > 0.0))
    {
      continue;
    }
    const double candidate = glm::dot(h - f * root, along) / length2;
    if (candidate >= -slack && candidate <= 1.0 + slack)
    {
      u = candidate;
      v = root;
      return std::isfinite(t);
    }
  }
  return false;
}
}

void RayCaster::ResolveHit(const glm::dvec3& origin,
  const glm::dvec3& direction,
  const TriangleHit& triangle,
  RayHit& hit,
  bool quadStart) const
{
  hit.Patch = triangle.Patch;
  hit.U = triangle.U;
  hit.V = triangle.V;
  hit.T = triangle.Distance;
  if (quadStart && this->Impl->Options.RefineHits && this->Impl->QuadsU[hit.Patch] == 1 &&
    this->Impl->QuadsV[hit.Patch] == 1)
  {
    // A convex planar quadrilateral (ChooseResolution's one quad): its exact (u, v, t) in closed
    // form, which the refinement below then only confirms (its first residual is within its
    // tolerance), instead of three to five Newton steps from the triangle's point.
    const BezierPatch& patch = *this->Impl->Patches[hit.Patch].Geometry;
    const int m = patch.DegreeU();
    const int n = patch.DegreeV();
    double u;
    double v;
    double t;
    if (QuadIntersection(patch.ControlPoint(0, 0),
          patch.ControlPoint(m, 0),
          patch.ControlPoint(m, n),
          patch.ControlPoint(0, n),
          origin,
          direction,
          u,
          v,
          t))
    {
      hit.U = u;
      hit.V = v;
      hit.T = t;
    }
  }
  if (this->Impl->Options.RefineHits)
  {
    double u = hit.U;
    double v = hit.V;
    double t = hit.T;
    if (this->Refine(hit.Patch, origin, direction, u, v, t))
    {
      hit.U = std::clamp(u, 0.0, 1.0);
      hit.V = std::clamp(v, 0.0, 1.0);
      hit.T = t;
    }
  }
  glm::dvec3 q;
  glm::dvec3 qu;
  glm::dvec3 qv;
  EvaluatePointAndPartials(*this->Impl->Patches[hit.Patch].Geometry, hit.U, hit.V, q, qu, qv);
  glm::dvec3 normal = glm::cross(qu, qv);
  if (!(glm::length(normal) > 0.0))
  {
    normal = triangle.TriangleNormal;
  }
  hit.FrontSide = glm::dot(normal, direction) < 0.0;
}

bool RayCaster::FirstHit(const glm::dvec3& origin,
  const glm::dvec3& direction,
  double tNear,
  std::size_t& patch,
  double& distance,
  bool& front) const
{
  // Every side counts: the caller asks which one it met.
  TriangleHit hit;
  if (!this->Intersect(origin, direction, static_cast<float>(tNear), RayFilter(), false, hit))
  {
    return false;
  }
  patch = hit.Patch;
  distance = hit.Distance;
  front = hit.FrontSide;
  return true;
}

void RayCaster::PatchesNear(const glm::dvec3& point,
  double radius,
  std::vector<std::size_t>& patches) const
{
  const Implementation& impl = *this->Impl;
  patches.clear();
  impl.BoundsTree->Traverse([&](const BoundingBoxTree::Node& node)
    { return node.Bounds.DistanceTo(point) <= radius; },
    [&](int32_t item)
    {
      if (impl.TriangleBounds[static_cast<std::size_t>(item)].DistanceTo(point) <= radius)
      {
        patches.push_back(static_cast<std::size_t>(item));
      }
    });
  std::sort(patches.begin(), patches.end());
}

std::size_t RayCaster::PatchCount() const
{
  return this->Impl->Patches.size();
}

std::size_t RayCaster::TriangleCount() const
{
  return this->Impl->Triangles;
}

std::size_t RayCaster::VertexCount() const
{
  return this->Impl->Vertices;
}

void RayCaster::Resolution(std::size_t patch, int& quadsU, int& quadsV) const
{
  quadsU = this->Impl->QuadsU[patch];
  quadsV = this->Impl->QuadsV[patch];
}

} // namespace sphcover
