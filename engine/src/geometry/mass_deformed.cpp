// SPDX-License-Identifier: MIT
// Mass properties by quadrature for tapered or bent superquadrics and for hyperquadrics. Integrals over
// the deformed body become integrals over the undeformed one by the change of variables
// ∫_D(B) g(q) dq = ∫_B g(D(p))·|det J(p)| dp, so the integration domain keeps its simple shape and only
// the smooth integrand changes; det J = (1 + kx·z/a3)(1 + ky·z/a3)(1 − k·u) (deform.cpp).
//
// Superquadric: per octant, Cartesian coordinates (X, Y, Z) = (x/a1, y/a2, z/a3) on the graph domain
// Y ≤ Ymax(X), Z ≤ Zmax(X, Y). The integrand is smooth; the boundary layers of box-like shapes sit at
// the interval ends, where tanh-sinh quadrature converges double-exponentially (bounded integrand).
// Powers are taken of complements (1 − X^(2/ε2) from log1p) so small ε keeps full precision.
// Hyperquadric: rays from an interior point over a cube-sphere grid of directions (Gauss-Legendre on
// panels), the surface distance by root-finding, Gauss-Legendre along each ray.
#include "geometry/mass_deformed.h"

#include "geometry/deform_internal.h"
#include "geometry/hyperquadric_solve.h"
#include "supermodal/geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace supermodal
{
namespace
{

/// tanh-sinh nodes span t ∈ [−4, 4]: there 1 − x ≈ e^(−π sinh 4) ≈ 1e-37, so the neglected tails of a
/// bounded integrand weigh < 1e-35.
constexpr double k_tanh_sinh_span = 4.0;
/// Gauss-Legendre points along z (superquadric) and along rays: with |k·z| < π the bent integrand is
/// an entire function of z, and 8 points integrate polynomials to degree 15 exactly (taper moments).
constexpr int k_line_points = 8;
/// Gauss-Legendre points per panel side of a cube face (hyperquadric directions).
constexpr int k_panel_points = 6;
constexpr int k_jacobi_sweeps = 50;

struct Node {
    double x = 0.0, complement = 1.0, weight = 0.0; // x ∈ (0, 1), 1 − x, weight
};

std::vector<Node> tanh_sinh(int count)
{
    const int half = std::max(count / 2, 1);
    const double h = k_tanh_sinh_span / half;
    std::vector<Node> nodes;
    for (int k = -half; k <= half; ++k) {
        const double t = k * h, s = std::numbers::pi * std::sinh(t);
        const double x = 1.0 / (1.0 + std::exp(-s)), xc = 1.0 / (1.0 + std::exp(s));
        nodes.push_back({x, xc, h * std::numbers::pi * std::cosh(t) * x * xc});
    }
    return nodes;
}

/// Gauss-Legendre nodes on (0, 1) by Newton on P_n (Golub-Welsch is not needed at these sizes).
std::vector<Node> gauss_legendre(int count)
{
    std::vector<Node> nodes;
    for (int i = 0; i < count; ++i) {
        double x = std::cos(std::numbers::pi * (i + 0.75) / (count + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= count; ++k) {
                const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = count * (x * p1 - p0) / (x * x - 1.0);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16)
                break;
        }
        nodes.push_back({0.5 * (1.0 + x), 0.5 * (1.0 - x), 1.0 / ((1.0 - x * x) * dp * dp)});
    }
    return nodes;
}

/// Running ∫|det J|, ∫|det J| q and ∫|det J| q qᵀ over the body.
struct Moments {
    double volume = 0.0;
    Vec3 first{};
    Mat3 second{};

    /// Undeformed point p with quadrature weight `weight`, mapped by d (arc: d's factors at p.z).
    void add(const Deformation& d, const Vec3& p, const BendArc& arc, double weight)
    {
        const Vec3 q = deform_with(d, p, arc);
        const double w = weight * std::abs(deform_determinant(d, p));
        volume += w;
        first += w * q;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                second.m[i][j] += w * q[i] * q[j];
    }

    /// The cone from c along unit d to distance r, solid-angle weight w, undeformed: ∫ρⁿ dρ in closed form.
    void add_ray(const Vec3& c, const Vec3& d, double r, double w)
    {
        const double r3 = w * r * r * r / 3.0, r4 = w * r * r * r * r / 4.0, r5 = w * r * r * r * r * r / 5.0;
        volume += r3;
        first += r3 * c + r4 * d;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                second.m[i][j] += r3 * c[i] * c[j] + r4 * (c[i] * d[j] + d[i] * c[j]) + r5 * d[i] * d[j];
    }
};

/// 1 − b^e for b ∈ [0, 1] given as its complement c = 1 − b, accurate when c or the result is tiny.
double one_minus_power(double c, double e)
{
    return c >= 1.0 ? 1.0 : -std::expm1(e * std::log1p(-c));
}

Moments superquadric_moments(const ShapeDef& shape, int order)
{
    const double e1 = shape.epsilon1, e2 = shape.epsilon2;
    const Vec3& a = shape.radii;
    const std::vector<Node> ts = tanh_sinh(8 * order + 1);
    const std::vector<Node> gl = gauss_legendre(k_line_points);
    const Deformation d = deformation_of(shape);
    Moments m;
    for (const Node& ne : ts) {
        // Half quadrant Y = η·X (and its mirror X = η·Y): the corner of a box-like cross-section lies on
        // η = 1, an end of the interval, rather than inside it.
        const double eta = ne.x;
        const double x_max = std::pow(1.0 + std::pow(eta, 2.0 / e2), -0.5 * e2);
        for (const Node& nr : ts) {
            // ρ = X/x_max is the cross-section's own radius: Zmax = (1 − ρ^(2/ε1))^(ε1/2).
            const double z_max = std::pow(one_minus_power(nr.complement, 2.0 / e1), 0.5 * e1);
            const double w = a.x * a.y * a.z * ne.weight * nr.weight * nr.x * x_max * x_max * z_max;
            if (!(w > 0.0))
                continue;
            const double u = nr.x * x_max, v = eta * u;
            for (const Node& nz : gl) {
                const double z = a.z * z_max * nz.x;
                // lift is even in z and rise odd: one evaluation serves both halves of the body.
                const BendArc up = bend_arc(d, z), down{up.lift, -up.rise};
                for (int half = 0; half < 2; ++half)
                    for (int octant = 0; octant < 8; ++octant) {
                        const double x = a.x * (half ? v : u), y = a.y * (half ? u : v);
                        m.add(d, {(octant & 1) ? -x : x, (octant & 2) ? -y : y, (octant & 4) ? -z : z},
                              (octant & 4) ? down : up, w * nz.weight);
                    }
            }
        }
    }
    return m;
}

Moments hyperquadric_moments(const ShapeDef& shape, int order)
{
    Moments m;
    const HyperquadricCenter center = hyperquadric_center(shape);
    if (!center.is_bounded || !center.is_non_empty)
        return m;
    const std::vector<Node> gl = gauss_legendre(k_panel_points);
    const std::vector<Node> line = gauss_legendre(k_line_points);
    const int panels = 2 * order;
    const bool deformed = is_deformed(shape);
    const Deformation deformation = deformation_of(shape);
    std::vector<double> coord, weight; // face parameter a ∈ [−1, 1] → tan(πa/4), weight with da/du
    for (int p = 0; p < panels; ++p)
        for (const Node& n : gl) {
            const double s = -1.0 + 2.0 * (p + n.x) / panels;
            const double u = std::tan(0.25 * std::numbers::pi * s);
            coord.push_back(u);
            weight.push_back(2.0 * n.weight / panels * 0.25 * std::numbers::pi * (1.0 + u * u));
        }
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2)
            for (size_t i = 0; i < coord.size(); ++i)
                for (size_t j = 0; j < coord.size(); ++j) {
                    Vec3 d;
                    d[axis] = sign;
                    d[(axis + 1) % 3] = coord[i];
                    d[(axis + 2) % 3] = coord[j];
                    const double len2 = dot(d, d);
                    // Solid angle of a cube-face patch: dω = du dv / (1 + u² + v²)^(3/2).
                    const double w_dir = weight[i] * weight[j] / (len2 * std::sqrt(len2));
                    d = d / std::sqrt(len2);
                    const double r = hyperquadric_ray_exit(shape, center.point, d);
                    if (!deformed) {
                        m.add_ray(center.point, d, r, w_dir);
                        continue;
                    }
                    for (const Node& n : line) {
                        const double rho = r * n.x;
                        const Vec3 p = center.point + rho * d;
                        m.add(deformation, p, bend_arc(deformation, p.z), w_dir * r * n.weight * rho * rho);
                    }
                }
    return m;
}

/// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations: a ← Vᵀ a V diagonal.
void jacobi_eigen(Mat3& a, Mat3& out_v)
{
    out_v = Mat3::identity();
    for (int sweep = 0; sweep < k_jacobi_sweeps; ++sweep) {
        const double off = a.m[0][1] * a.m[0][1] + a.m[0][2] * a.m[0][2] + a.m[1][2] * a.m[1][2];
        const double diag = a.m[0][0] * a.m[0][0] + a.m[1][1] * a.m[1][1] + a.m[2][2] * a.m[2][2];
        if (!(off > 1e-32 * diag))
            return;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (a.m[p][q] == 0.0)
                    continue;
                const double theta = 0.5 * (a.m[q][q] - a.m[p][p]) / a.m[p][q];
                const double t =
                    std::copysign(1.0, theta) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                Mat3 r = Mat3::identity();
                r.m[p][p] = c;
                r.m[q][q] = c;
                r.m[p][q] = s;
                r.m[q][p] = -s;
                a = transpose(r) * a * r;
                out_v = out_v * r;
            }
    }
}

/// Unit quaternion of a proper rotation matrix (Shepperd: divide by the largest of the four candidates).
Quat quat_from_rotation_matrix(const Mat3& r)
{
    const double t = r.m[0][0] + r.m[1][1] + r.m[2][2];
    Quat q;
    if (t >= r.m[0][0] && t >= r.m[1][1] && t >= r.m[2][2]) {
        const double s = 2.0 * std::sqrt(1.0 + t);
        q = {0.25 * s, (r.m[2][1] - r.m[1][2]) / s, (r.m[0][2] - r.m[2][0]) / s, (r.m[1][0] - r.m[0][1]) / s};
    } else if (r.m[0][0] >= r.m[1][1] && r.m[0][0] >= r.m[2][2]) {
        const double s = 2.0 * std::sqrt(1.0 + r.m[0][0] - r.m[1][1] - r.m[2][2]);
        q = {(r.m[2][1] - r.m[1][2]) / s, 0.25 * s, (r.m[0][1] + r.m[1][0]) / s, (r.m[0][2] + r.m[2][0]) / s};
    } else if (r.m[1][1] >= r.m[2][2]) {
        const double s = 2.0 * std::sqrt(1.0 + r.m[1][1] - r.m[0][0] - r.m[2][2]);
        q = {(r.m[0][2] - r.m[2][0]) / s, (r.m[0][1] + r.m[1][0]) / s, 0.25 * s, (r.m[1][2] + r.m[2][1]) / s};
    } else {
        const double s = 2.0 * std::sqrt(1.0 + r.m[2][2] - r.m[0][0] - r.m[1][1]);
        q = {(r.m[1][0] - r.m[0][1]) / s, (r.m[0][2] + r.m[2][0]) / s, (r.m[1][2] + r.m[2][1]) / s, 0.25 * s};
    }
    return normalized(q);
}

} // namespace

QuadratureMass quadrature_mass(const ShapeDef& def, double density, int order)
{
    QuadratureMass out;
    order = std::max(order, 1);
    Moments m;
    if (def.type == ShapeType::Superquadric)
        m = superquadric_moments(def, order);
    else if (def.type == ShapeType::Hyperquadric)
        m = hyperquadric_moments(def, order);
    if (!(m.volume > 0.0) || !std::isfinite(m.volume))
        return out;
    MassProperties& mp = out.properties;
    mp.volume = m.volume;
    mp.mass = density * m.volume;
    mp.center_of_mass = m.first / m.volume;
    // Second moment about the centre of mass S = ρ(∫q qᵀ − V c cᵀ); inertia I = tr(S)·1 − S.
    Mat3 s;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            s.m[i][j] = density * (m.second.m[i][j] - m.first[i] * m.first[j] / m.volume);
    const double trace = s.m[0][0] + s.m[1][1] + s.m[2][2];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            out.inertia_tensor.m[i][j] = (i == j ? trace : 0.0) - s.m[i][j];
    Mat3 diag = out.inertia_tensor, axes;
    jacobi_eigen(diag, axes);
    // Give each shape axis the principal axis most aligned with it, largest alignment first, so small
    // deformations keep the moments in the slots of the undeformed shape.
    bool slot_used[3] = {false, false, false}, axis_used[3] = {false, false, false};
    for (int round = 0; round < 3; ++round) {
        int best_slot = 0, best_axis = 0;
        double best = -1.0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (!slot_used[i] && !axis_used[j] && std::abs(axes.m[i][j]) > best) {
                    best = std::abs(axes.m[i][j]);
                    best_slot = i;
                    best_axis = j;
                }
        slot_used[best_slot] = axis_used[best_axis] = true;
        mp.inertia_diagonal[best_slot] = diag.m[best_axis][best_axis];
        const double sign = axes.m[best_slot][best_axis] < 0.0 ? -1.0 : 1.0;
        for (int r = 0; r < 3; ++r)
            out.principal_axes.m[r][best_slot] = sign * axes.m[r][best_axis];
    }
    // A right-handed frame, so that it is a rotation: flip the least aligned axis if needed (a principal
    // axis of either sign is one).
    const Mat3& pa = out.principal_axes;
    if (dot(pa.col(0), cross(pa.col(1), pa.col(2))) < 0.0) {
        int least = 0;
        for (int i = 1; i < 3; ++i)
            if (std::abs(pa.m[i][i]) < std::abs(pa.m[least][least]))
                least = i;
        for (int r = 0; r < 3; ++r)
            out.principal_axes.m[r][least] = -out.principal_axes.m[r][least];
    }
    mp.principal_axes = quat_from_rotation_matrix(out.principal_axes);
    return out;
}

} // namespace supermodal
