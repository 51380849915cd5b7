// Tests for engine/src/contact/face_contact.cpp and the support map it rests on: points on the true
// surfaces, the face manifold of a box resting on a box, warm against cold queries, the support count.
#include "contact/face_contact.h"
#include "contact/manifold.h"
#include "contact/penetration.h"
#include "support/shapes.h"

#include <cmath>
#include <gtest/gtest.h>

namespace sm = supermodal;

namespace
{

struct Rng {
    uint32_t seed = 5;
    double next()
    {
        seed = seed * 1664525u + 1013904223u;
        return static_cast<double>(seed >> 8) / 8388608.0 - 1.0;
    }
    sm::Vec3 unit() { return sm::normalized(sm::Vec3{next(), next(), next()}); }
};

sm::Collider box_collider(double half, double eps)
{
    return sm::make_collider(sm::test::superquadric({half, half, half}, eps, eps), {}, 0.0, 4000);
}

// How far a world point is off a body's surface, as the gauge F^(ε1/2) − 1 (a distance relative to
// the radius along that line) [-].
double off_surface(const sm::BodyView& body, const sm::Vec3& p)
{
    const sm::Collider& c = *body.collider;
    return std::abs(
        sm::contact_measure(c.shape, sm::inv_rotate(body.orientation, p - body.position) + c.com_shape));
}

sm::BodyView view(const sm::Collider& c, sm::Vec3 position, sm::Quat orientation = {})
{
    sm::BodyView v{&c, position, orientation, {}};
    v.box = sm::world_aabb(c.shape, position, orientation);
    return v;
}

} // namespace

TEST(SupportMapBound, PointsLieOnTheSurfaceWhereTheNormalIsTheDirection)
{
    // ε from 0.1 (nearly a box) to 2 (the octahedron's hull), unequal radii, random directions: the
    // support point's gauge is 1 within 1e-14 (so it is within 1e-14 of a radius of the true surface),
    // and where the surface is smooth (ε < 2, away from the axis planes) its normal is the direction
    // within 1e-9 rad.
    Rng rng;
    const double eps[] = {0.1, 0.2, 0.3, 0.5, 0.8, 1.0, 1.3, 1.7, 2.0};
    for (double e1 : eps)
        for (double e2 : eps) {
            const sm::ShapeDef s = sm::test::superquadric({0.05, 0.11, 0.03}, e1, e2);
            for (int k = 0; k < 200; ++k) {
                const sm::Vec3 d = rng.unit();
                const sm::Vec3 x = sm::support_point(s, d);
                ASSERT_LT(std::abs(sm::contact_measure(s, x)), 1e-14) << e1 << " " << e2;
                if (e1 >= 1.9 || e2 >= 1.9 || std::min({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) < 0.05)
                    continue;
                const sm::Vec3 n = sm::normalized(sm::contact_measure_gradient(s, x));
                EXPECT_LT(sm::length(sm::cross(n, d)), 1e-9) << e1 << " " << e2;
                EXPECT_GT(sm::dot(n, d), 0.0);
            }
        }
}

TEST(FaceContact, BoxRestingFlatOnABoxTouchesAtItsPatchCorners)
{
    // Two sharp ε = 0.1 boxes (half 0.1 m), the upper 1 mm into the lower, faces aligned: the face path
    // (two support-map evaluations) gives four points at the corners of the patches, (±w, ±w) with w
    // where the face has dropped a quarter of the overlap (0.25 mm), each a point of both true surfaces
    // within 1e-12, between half the overlap and the overlap deep, along the face normal.
    const sm::Collider box = box_collider(0.1, 0.1);
    const sm::BodyView lower = view(box, {}), upper = view(box, {0, 0.199, 0});
    sm::PairManifold m;
    std::vector<sm::ContactPoint> pts;
    sm::QueryCost cost;
    ASSERT_EQ(sm::collide_manifold(upper, lower, m, pts, false, &cost), 4);
    EXPECT_EQ(cost.support_calls, 2);
    const double w = sm::face_patch(box.shape, 1, 0.25e-3).half[0];
    EXPECT_GT(w, 0.08);
    for (int i = 0; i < m.count; ++i) {
        const sm::Vec3 on_a = upper.position + m.points[i].local_a;
        const sm::Vec3 on_b = lower.position + m.points[i].local_b;
        EXPECT_LT(off_surface(upper, on_a), 1e-12);
        EXPECT_LT(off_surface(lower, on_b), 1e-12);
        EXPECT_NEAR(std::abs(on_a.x), w, 1e-9);
        EXPECT_NEAR(std::abs(on_a.z), w, 1e-9);
    }
    for (const sm::ContactPoint& p : pts) {
        EXPECT_GE(p.depth, 0.5e-3 - 1e-12);
        EXPECT_LE(p.depth, 1e-3 + 1e-12);
        EXPECT_EQ(p.normal, (sm::Vec3{0, 1, 0}));
    }
}

TEST(FaceContact, BoxAcrossTwoMeetsOnAStripInTheMiddle)
{
    // A rounded ε = 0.3 box (half 0.1 m) across the gap beside another, its face 1 mm below the other's
    // pole plane, 0.105 m off to the side: the upper does not reach under the lower's pole, and the
    // patches round the poles never meet. The faces drop towards their edges and meet halfway across
    // where their outlines overlap (x from −0.1 to −0.005: x = −0.0525), on a strip along z: every point
    // lies there, on both true surfaces within 1e-12, touching, and the middle one is deeper than the
    // surfaces' overlap 2 mm to either side of it (where they meet is where they overlap most).
    const sm::Collider box = box_collider(0.1, 0.3);
    const sm::BodyView lower = view(box, {-0.105, 0, 0}), upper = view(box, {0, 0.199, 0});
    const sm::FaceContact fc = sm::face_contact(upper, lower, {0, 1, 0});
    ASSERT_EQ(fc.kind, sm::FaceContact::Kind::Faces);
    ASSERT_EQ(fc.count, 3);
    double middle_depth = 0.0;
    for (int i = 0; i < fc.count; ++i) {
        const sm::FacePoint& p = fc.points[static_cast<size_t>(i)];
        EXPECT_NEAR(p.on_a.x, -0.0525, 1e-12);
        EXPECT_LT(off_surface(upper, p.on_a), 1e-12);
        EXPECT_LT(off_surface(lower, p.on_b), 1e-12);
        EXPECT_GT(p.depth, 0.0);
        EXPECT_NEAR(std::abs(fc.normal.y), 1.0, 1e-12);
        if (std::abs(p.on_a.z) < 1e-12)
            middle_depth = p.depth;
    }
    EXPECT_GT(middle_depth, 0.5e-3); // the faces drop about 0.2 mm each there, from 1 mm
    // The surfaces' overlap along y at x [m], z = 0, from each face's height.
    auto overlap_at = [&](double x) {
        sm::Vec3 top{x + 0.105, 0, 0}, bottom{x, 0, 0};
        EXPECT_TRUE(sm::face_height(box.shape, 1, 1.0, top));
        EXPECT_TRUE(sm::face_height(box.shape, 1, -1.0, bottom));
        return top.y - (0.199 + bottom.y);
    };
    EXPECT_NEAR(overlap_at(-0.0525), middle_depth, 1e-12);
    EXPECT_LT(overlap_at(-0.0545), middle_depth);
    EXPECT_LT(overlap_at(-0.0505), middle_depth);
}

TEST(FaceContact, EveryPointLiesOnBothTrueSurfaces)
{
    // Rounded boxes (ε 0.2 to 0.5) in random poses 1 mm or less into each other, face on face, edge on
    // face and edge across edge: every point the face path gives is a point of both surfaces within
    // 1e-12 (the stated bound: the lifts solve the surface equation to that), and as deep as said.
    Rng rng;
    int faces = 0, edges = 0;
    for (double eps : {0.2, 0.3, 0.5}) {
        const sm::Collider box = box_collider(0.05, eps);
        for (int k = 0; k < 300; ++k) {
            // Two in three nearly aligned (faces), one in three turned anyhow (edges and corners).
            const double spread = k % 3 == 0 ? 1.0 : 0.02;
            const sm::Quat qa =
                sm::normalized(sm::Quat{1.0, spread * rng.next(), spread * rng.next(), spread * rng.next()});
            const sm::Quat qb =
                sm::normalized(sm::Quat{1.0, spread * rng.next(), rng.next(), spread * rng.next()});
            const sm::BodyView b = view(box, {}, qb);
            const sm::Vec3 dir = sm::normalized(sm::Vec3{0.4 * rng.next(), 1.0, 0.4 * rng.next()});
            double lo = 0.0, hi = 0.3; // bisection on the face query's own verdict
            for (int i = 0; i < 50; ++i) {
                const double mid = 0.5 * (lo + hi);
                const sm::FaceContact fc = sm::face_contact(view(box, mid * dir, qa), b, dir);
                (fc.kind == sm::FaceContact::Kind::Apart ? hi : lo) = mid;
            }
            const sm::BodyView a = view(box, (lo - 1e-3 * (0.2 + 0.8 * std::abs(rng.next()))) * dir, qa);
            const sm::FaceContact fc = sm::face_contact(a, b, dir);
            faces += fc.kind == sm::FaceContact::Kind::Faces ? 1 : 0;
            edges += fc.kind == sm::FaceContact::Kind::Edge ? 1 : 0;
            for (int i = 0; i < fc.count; ++i) {
                const sm::FacePoint& p = fc.points[static_cast<size_t>(i)];
                EXPECT_LT(off_surface(a, p.on_a), 1e-12);
                EXPECT_LT(off_surface(b, p.on_b), 1e-12);
                EXPECT_GT(p.depth, 0.0);
                EXPECT_NEAR(p.depth, sm::dot(p.on_b - p.on_a, fc.normal), 1e-12);
            }
        }
    }
    EXPECT_GT(faces, 300);
    EXPECT_GT(edges, 10);
}

TEST(FaceContact, WarmStartedQueryEqualsTheColdOne)
{
    // A rounded box tilted on another: the query from the last normal (the cold query's, turned by
    // 1e-3 rad as a resting pair's drifts in a step) keeps the cold query's reference face, so its
    // manifold is the same, bit for bit (faces within 2e-3 rad of parallel may take either: skipped);
    // and the least-overlap search of the general path from a normal 0.02 rad off finds the cold
    // search's depth within 1e-9 m on rounded corners (the search stops when Newton predicts less than
    // k_penetration_depth_tolerance = 1e-9 m left to remove) and its normal within 5e-4 rad (near the
    // minimum the overlap grows as ½·H·δ² with H, the two corners' summed radii of curvature, above
    // 8 mm here (a 2-D section of the corner has 11 mm): δ = √(2·1e-9 / 8e-3) = 5e-4 rad; measured up to
    // 1.6e-4).
    Rng rng;
    const sm::Collider box = box_collider(0.05, 0.3);
    for (int k = 0; k < 50; ++k) {
        const sm::Quat q =
            sm::normalized(sm::Quat{1.0, 0.05 * rng.next(), 0.1 * rng.next(), 0.05 * rng.next()});
        const sm::BodyView lower = view(box, {}),
                           upper = view(box, {0.01 * rng.next(), 0.0995, 0.01 * rng.next()}, q);
        const sm::FaceContact cold = sm::face_contact(upper, lower, sm::normalized(upper.position));
        ASSERT_EQ(cold.kind, sm::FaceContact::Kind::Faces);
        if (std::abs(sm::rotate(q, {0, 1, 0}).y) > std::cos(2e-3))
            continue;
        const sm::Vec3 turn = sm::normalized(sm::cross(cold.normal, rng.unit()));
        const sm::FaceContact warm =
            sm::face_contact(upper, lower, sm::normalized(cold.normal + 1e-3 * turn));
        ASSERT_EQ(warm.kind, cold.kind);
        EXPECT_EQ(warm.normal, cold.normal);
        ASSERT_EQ(warm.count, cold.count);
        for (int i = 0; i < cold.count; ++i)
            EXPECT_EQ(warm.points[static_cast<size_t>(i)].depth, cold.points[static_cast<size_t>(i)].depth);
    }
    int compared = 0;
    for (int k = 0; k < 60; ++k) {
        // corner on corner: both turned by a random rotation
        const sm::BodyView b =
            view(box, {}, sm::normalized(sm::Quat{rng.next(), rng.next(), rng.next(), rng.next()}));
        const sm::Quat qa = sm::normalized(sm::Quat{rng.next(), rng.next(), rng.next(), rng.next()});
        const sm::Vec3 dir = rng.unit();
        double lo = 0.0, hi = 0.3;
        for (int i = 0; i < 50; ++i) {
            const double mid = 0.5 * (lo + hi);
            (sm::find_penetration(view(box, mid * dir, qa), b, {}, sm::PenetrationTarget::LeastOverlap).hit
                 ? lo
                 : hi) = mid;
        }
        const sm::BodyView a = view(box, (lo - 5e-4) * dir, qa);
        const sm::Penetration cold = sm::find_penetration(a, b, {}, sm::PenetrationTarget::LeastOverlap);
        if (!cold.converged)
            continue;
        ++compared;
        const sm::Vec3 turn = sm::normalized(sm::cross(cold.normal, rng.unit()));
        const sm::Penetration warm = sm::find_penetration(a, b, sm::normalized(cold.normal + 0.02 * turn),
                                                          sm::PenetrationTarget::LeastOverlap);
        ASSERT_TRUE(warm.hit);
        EXPECT_LT(std::acos(std::min(1.0, sm::dot(warm.normal, cold.normal))), 5e-4);
        EXPECT_NEAR(warm.depth, cold.depth, 1e-9);
    }
    EXPECT_GT(compared, 20);
}

TEST(FaceContact, APairApartTriesItsSeparatingFaceFirst)
{
    // Two boxes side by side along x, B turned 0.3 rad about y, about 1 mm apart: the first query
    // proves them apart along A's face axis and keeps it; the next costs one support-map evaluation
    // (B's extent along it; A's is its radius). Two boxes turned alike would cost none.
    const sm::Collider box = box_collider(0.05, 0.3);
    const sm::BodyView a = view(box, {0.117, 0, 0}),
                       b = view(box, {}, {std::cos(0.15), 0, std::sin(0.15), 0});
    sm::PairManifold m;
    std::vector<sm::ContactPoint> pts;
    sm::QueryCost first, second;
    EXPECT_EQ(sm::collide_manifold(a, b, m, pts, false, &first), 0);
    EXPECT_EQ(m.count, 0);
    EXPECT_GT(sm::length(m.normal), 0.5);
    EXPECT_EQ(sm::collide_manifold(a, b, m, pts, false, &second), 0);
    EXPECT_EQ(second.support_calls, 1);
    // That query proved them apart: unmoved, the next one is free.
    sm::QueryCost third;
    EXPECT_EQ(sm::collide_manifold(a, b, m, pts, false, &third), 0);
    EXPECT_EQ(third.support_calls, 0);
}

TEST(FaceContact, AProofOfBeingApartSkipsOnlyQueriesThatWouldFindTheSame)
{
    // Two rounded boxes 4 mm apart drift together and turn a little each step (random small motions,
    // 300 steps, they end up touching): a query kept by its proof of being apart gives the same manifold
    // (normal, points, bit for bit) and the same contact points as the same query with the proof
    // dropped, while it saves evaluations. A reshaped body (another collider) voids the proof.
    Rng rng;
    const sm::Collider box = box_collider(0.05, 0.3), bigger = box_collider(0.06, 0.3);
    sm::Vec3 pa{0.125, 0.003, 0.0};
    sm::Quat qb{std::cos(0.1), 0.0, std::sin(0.1), 0.0}, qa{};
    sm::PairManifold kept, fresh;
    int saved = 0, skipped = 0;
    for (int step = 0; step < 300; ++step) {
        pa = pa + sm::Vec3{-9e-5 + 2e-5 * rng.next(), 1e-5 * rng.next(), 1e-5 * rng.next()};
        qa = sm::normalized(
            sm::quat_from_rotation_vector({1e-4 * rng.next(), 1e-4 * rng.next(), 1e-4 * rng.next()}) * qa);
        const sm::BodyView a = view(box, pa, qa), b = view(box, {}, qb);
        fresh.apart = {};
        std::vector<sm::ContactPoint> with_proof, without;
        sm::QueryCost cost_kept, cost_fresh;
        const int n_kept = sm::collide_manifold(a, b, kept, with_proof, true, &cost_kept);
        const int n_fresh = sm::collide_manifold(a, b, fresh, without, true, &cost_fresh);
        ASSERT_EQ(n_kept, n_fresh) << "step " << step;
        ASSERT_EQ(kept.count, fresh.count) << "step " << step;
        ASSERT_EQ(kept.normal, fresh.normal) << "step " << step;
        for (int i = 0; i < kept.count; ++i) {
            EXPECT_EQ(kept.points[static_cast<size_t>(i)].local_a,
                      fresh.points[static_cast<size_t>(i)].local_a);
            EXPECT_EQ(kept.points[static_cast<size_t>(i)].local_b,
                      fresh.points[static_cast<size_t>(i)].local_b);
        }
        for (size_t i = 0; i < with_proof.size(); ++i) {
            EXPECT_EQ(with_proof[i].point, without[i].point);
            EXPECT_EQ(with_proof[i].depth, without[i].depth);
        }
        saved += cost_fresh.support_calls - cost_kept.support_calls;
        skipped += cost_kept.support_calls == 0 && cost_fresh.support_calls > 0 ? 1 : 0;
    }
    EXPECT_GT(kept.count, 0); // they touch in the end
    EXPECT_GT(skipped, 50);
    EXPECT_GT(saved, 50);
    // Unmoved and apart: proven, then free; reshaped A: evaluated again.
    sm::PairManifold m;
    std::vector<sm::ContactPoint> pts;
    const sm::BodyView a = view(box, {0.11, 0, 0}), b = view(box, {}, qb);
    sm::QueryCost first, second, reshaped;
    (void)sm::collide_manifold(a, b, m, pts, true, &first);
    (void)sm::collide_manifold(a, b, m, pts, true, &first);
    (void)sm::collide_manifold(a, b, m, pts, true, &second);
    EXPECT_EQ(second.support_calls, 0);
    (void)sm::collide_manifold(view(bigger, {0.11, 0, 0}), b, m, pts, true, &reshaped);
    EXPECT_GT(reshaped.support_calls, 0);
}
