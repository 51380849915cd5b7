// SPDX-License-Identifier: MIT
// The Bullet peer of the benchmarks: a btDiscreteDynamicsWorld built from the same SceneSpec as
// supermodal's world. Built only when Bullet is found (SM_BENCH_BULLET); the engine never links it.
#pragma once

#include "peer/peer_scene.h"

#include <memory>
#include <string>

namespace peer
{

/// Bullet settings the benchmarks vary; everything else is Bullet's default (sequential impulses,
/// 10 iterations, split impulse off, one thread).
struct BulletOptions {
    bool deactivation = false; ///< Let resting bodies sleep (Bullet's default thresholds and 2 s).
    /// Collision margin of boxes and ellipsoids [m]. A box keeps its outer half extents (box–box contact
    /// is exact); the margin rounds its edges against planes. Bullet's default 0.04 m is meant for
    /// bodies of about 1 m: it would exceed the ellipsoid's 0.03 m radius.
    double margin = 0.01;
};

/// Bullet's world for a scene: one internal step of scene.dt per step().
[[nodiscard]] std::unique_ptr<PeerWorld> make_bullet_world(const SceneSpec& scene,
                                                           const BulletOptions& options);

/// "Bullet 3.24 (float)": version and scalar precision of the library linked.
[[nodiscard]] std::string bullet_name();

} // namespace peer
