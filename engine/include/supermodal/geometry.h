// SPDX-License-Identifier: MIT
// The shape layer every other system queries: inside-outside functions, normals, parametric surfaces,
// support maps, bounds, surface samples and meshes of superquadrics and hyperquadrics, with Barr's taper
// and bend. Points are in the shape frame (Barr: z is the polar axis) unless a name says otherwise.
// Every function returns finite numbers for every finite input, including ε from 0.01 to 4, points at
// the centre, on the axes and 10^6 radii away.
#pragma once

#include "supermodal/api.h"
#include "supermodal/math.h"
#include "supermodal/shape.h"

#include <cstdint>
#include <vector>

namespace supermodal
{

// ---- Superquadric inside-outside (undeformed shape) ------------------------------------------------

/// Natural log of Barr's inside-outside function ln F(p) (F < 1 inside), evaluated in log space so it
/// never overflows. At the exact centre returns a large negative finite value (−1e300).
[[nodiscard]] SM_API double inside_outside_log(const ShapeDef& shape, const Vec3& p);
/// F(p) itself, saturating at 1e300 instead of overflowing [-].
[[nodiscard]] SM_API double inside_outside(const ShapeDef& shape, const Vec3& p);
/// The well-scaled contact measure F^(ε1/2) − 1 [-]: −1 at the centre, 0 on the surface, and roughly
/// (distance along the ray from the centre) / (radius along that ray) outside. Finite everywhere.
[[nodiscard]] SM_API double contact_measure(const ShapeDef& shape, const Vec3& p);
/// Gradient of contact_measure [1/m]; finite everywhere (zero at the centre).
[[nodiscard]] SM_API Vec3 contact_measure_gradient(const ShapeDef& shape, const Vec3& p);
/// Unit outward normal of the level set through p (direction of the gradient); for p at the centre,
/// returns +z.
[[nodiscard]] SM_API Vec3 implicit_normal(const ShapeDef& shape, const Vec3& p);

// ---- Superquadric parametric surface ----------------------------------------------------------------

/// sign(x)·|x|^e, the signed power of Barr's parametric form.
[[nodiscard]] SM_API double signed_power(double x, double e);
/// Surface point at latitude eta ∈ [−π/2, π/2] and longitude omega ∈ [−π, π] [m].
[[nodiscard]] SM_API Vec3 surface_point(const ShapeDef& shape, double eta, double omega);
/// Unit outward normal at (eta, omega); finite at the poles and at ε → 0 edges.
[[nodiscard]] SM_API Vec3 surface_normal(const ShapeDef& shape, double eta, double omega);

// ---- Distances, projections, support, bounds --------------------------------------------------------

/// Signed distance from p to the surface along the ray from the centre through p [m]: |p|·(1 − F^(−ε1/2)).
/// Negative inside. An upper bound on the true distance's magnitude.
[[nodiscard]] SM_API double radial_distance(const ShapeDef& shape, const Vec3& p);

/// Result of an approximate closest-point projection.
struct SurfaceProjection {
    Vec3 point{};             ///< Closest surface point found [m].
    Vec3 normal{};            ///< Unit outward normal there.
    double distance = 0.0;    ///< Signed distance p − point along the normal [m], negative inside.
    double error_bound = 0.0; ///< Bound on |found distance| − |true distance| [m] (see docs/geometry.md).
    int iterations = 0;
    bool converged = false;
};
/// Closest point on the (undeformed) superquadric surface to p.
[[nodiscard]] SM_API SurfaceProjection closest_point(const ShapeDef& shape, const Vec3& p);

/// Support point: argmax over the shape of dot(direction, x) [m], shape frame. Exact (dual
/// superquadric, exponents 2 − ε) for convex superquadrics (ε1, ε2 ≤ 2); for others, the support of
/// the convex hull. direction need not be unit; zero gives the +z pole.
[[nodiscard]] SM_API Vec3 support_point(const ShapeDef& shape, const Vec3& direction);

/// Axis-aligned box [m].
struct Aabb {
    Vec3 min{};
    Vec3 max{};
};
/// Tight world-space box of the shape at a pose (taper and bend included). Planes give ±1e300.
/// Deformed superquadrics and hyperquadrics bound a mesh whose vertices are computed once per distinct
/// shape and cached process-wide (thread-safe; the result is bit-identical to recomputing).
[[nodiscard]] SM_API Aabb world_aabb(const ShapeDef& shape, const Vec3& position, const Quat& orientation);

// ---- Barr deformations (taper, then bend, along the polar axis z) -----------------------------------

/// True if the shape has a non-zero taper or bend.
[[nodiscard]] SM_API bool is_deformed(const ShapeDef& shape);
/// Undeformed shape point → deformed shape point [m].
[[nodiscard]] SM_API Vec3 deform_point(const ShapeDef& shape, const Vec3& p);
/// Jacobian ∂deform_point/∂p at p [-].
[[nodiscard]] SM_API Mat3 deform_jacobian(const ShapeDef& shape, const Vec3& p);
/// Normal at deformed point through the inverse-transpose of the Jacobian at undeformed p; unit.
[[nodiscard]] SM_API Vec3 deform_normal(const ShapeDef& shape, const Vec3& p, const Vec3& normal);
/// Result of inverting the deformation.
struct UndeformResult {
    Vec3 point{}; ///< Undeformed point [m] (best estimate even when !converged; always finite).
    bool converged = false;
    int iterations = 0;
};
/// Deformed point → undeformed point by Newton's method with a convergence guard.
[[nodiscard]] SM_API UndeformResult undeform_point(const ShapeDef& shape, const Vec3& q);
/// Contact measure of a possibly deformed superquadric or hyperquadric at shape point q: through the
/// inverse map when deformed. Where the inverse fails, returns a conservative positive value (outside).
[[nodiscard]] SM_API double shape_measure(const ShapeDef& shape, const Vec3& q);

// ---- Hyperquadrics -----------------------------------------------------------------------------------

/// H(p) = Σ |n_i·p + d_i|^γ_i (H < 1 inside), saturating at 1e300.
[[nodiscard]] SM_API double hyperquadric_value(const ShapeDef& shape, const Vec3& p);
/// Unit outward normal ∇H/|∇H| at p.
[[nodiscard]] SM_API Vec3 hyperquadric_normal(const ShapeDef& shape, const Vec3& p);

// ---- Surface samples and meshes ----------------------------------------------------------------------

/// A surface sample: where it is, which way it faces, and how much surface it stands for.
struct SurfaceSample {
    Vec3 point{};      ///< [m], shape frame (deformed when the shape is).
    Vec3 normal{};     ///< Unit outward normal.
    double area = 0.0; ///< Surface area this sample stands for [m²]; the areas sum to the surface area.
};
/// Samples spaced about `spacing` [m] apart along the surface, evenly (not bunched at edges), with
/// areas. Count grows like area / spacing²; capped at max_count (spacing is widened to fit).
[[nodiscard]] SM_API std::vector<SurfaceSample> sample_surface(const ShapeDef& shape, double spacing,
                                                               int max_count = 100000);

/// Indexed triangle mesh with per-vertex normals, shape frame. Watertight: every edge is shared by
/// exactly two triangles; no degenerate triangles.
struct TriangleMesh {
    std::vector<Vec3> positions;   ///< [m].
    std::vector<Vec3> normals;     ///< Unit, per vertex.
    std::vector<uint32_t> indices; ///< Three per triangle, counter-clockwise seen from outside.
};
/// Tessellates the shape with about `resolution` segments around the equator (≥ 4); deformed shapes
/// and hyperquadrics included.
[[nodiscard]] SM_API TriangleMesh tessellate(const ShapeDef& shape, int resolution);
/// How tessellate() spaces a superquadric's vertices along its loop and meridian.
enum class MeshSpacing : uint8_t {
    EqualArc,  ///< Even arc length: even triangles (deformation, sampling, export).
    Curvature, ///< Closer where the surface turns (∫√κ ds and a floor): an even gap between mesh and
               ///< surface, so fewer segments for the same silhouette (rendering rigid bodies).
};
/// tessellate() with a choice of spacing; `resolution` still counts the equator's segments.
[[nodiscard]] SM_API TriangleMesh tessellate(const ShapeDef& shape, int resolution, MeshSpacing spacing);
/// About the largest gap [m] between a superquadric's Curvature-spaced mesh at `resolution` and its
/// surface (the spacing measure's steps along the loop and the meridian, each squared over 8 as for
/// a chord of a circle, added); it falls as
/// 1/resolution². Near a sharp rim the mesh keeps the rim's middle as a vertex, and the gap there is
/// at most 0.3 of the rim's radius. Taper and bend are not counted. 0 for other shapes.
[[nodiscard]] SM_API double tessellation_gap(const ShapeDef& shape, int resolution);
/// Enclosed volume of a closed mesh (divergence theorem) [m³].
[[nodiscard]] SM_API double mesh_volume(const TriangleMesh& mesh);

} // namespace supermodal
