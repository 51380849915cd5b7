// SPDX-License-Identifier: MIT
// Engine-neutral scenes for the peer benchmarks (bench/peer_pile.cpp, bench/stack_bench.cpp): one
// description that each engine builds its own world from, and the few queries the benchmarks need, so
// the measuring loops are the same code for supermodal and for the peer (Bullet, bench/peer/bullet_world.h).
#pragma once

#include "supermodal/contact.h"
#include "supermodal/math.h"
#include "supermodal/shape.h"

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace peer
{

namespace sm = supermodal;

/// The bodies both engines have. supermodal's box is a rounded superquadric box (ε = 0.3).
enum class Kind { Box, Sphere, Ellipsoid };

[[nodiscard]] std::string_view kind_name(Kind kind);

/// A static half-space {x : normal·x ≤ offset} (floor, walls).
struct PlaneSpec {
    sm::Vec3 normal{0, 1, 0}; ///< Outward normal, unit, world.
    double offset = 0.0;      ///< [m].
};

struct BodySpec {
    Kind kind = Kind::Box;
    sm::Vec3 half{0.05, 0.05, 0.05}; ///< Half extents (box) or radii (sphere, ellipsoid) [m], body frame.
    sm::Vec3 position{};             ///< Centre [m], world.
    sm::Quat orientation{};          ///< world_from_body, unit.
};

/// What both engines share: same gravity, friction, restitution, mass and step.
struct SceneSpec {
    double dt = 1.0 / 240.0;       ///< Step [s].
    sm::Vec3 gravity{0, -9.81, 0}; ///< [m/s²].
    double friction = 0.5;         ///< Coulomb coefficient of every pair [-].
    double restitution = 0.0;      ///< [-].
    double density = 1000.0;       ///< [kg/m³]: mass and inertia of supermodal's shape, in both engines.
    std::vector<PlaneSpec> planes;
    std::vector<BodySpec> bodies;
};

/// A stepped world of either engine, seen through what the benchmarks measure.
class PeerWorld
{
  public:
    virtual ~PeerWorld() = default;
    virtual void step() = 0;
    /// Deepest overlap of any touching pair after the last step [m], ≥ 0.
    [[nodiscard]] virtual double max_penetration() const = 0;
    [[nodiscard]] virtual sm::Vec3 position(int body) const = 0; ///< Centre of body (spec order) [m].
    [[nodiscard]] virtual double speed(int body) const = 0;      ///< |v| of its centre of mass [m/s].
};

/// supermodal settings the benchmarks vary; everything else is the engine's default.
struct SupermodalOptions {
    int substeps = 1;
    sm::ContactDef contact{};
};

/// supermodal's shape for a body: the box is rounded (ε = 0.3), the others are ellipsoids.
[[nodiscard]] sm::ShapeDef supermodal_shape(const BodySpec& body);

/// supermodal's world for a scene, one thread.
[[nodiscard]] std::unique_ptr<PeerWorld> make_supermodal_world(const SceneSpec& scene,
                                                               const SupermodalOptions& options);

/// Sets one ContactDef field from "key=value" (the names are the fields'; enums by their lower-case
/// names). Returns an empty string, or what was wrong.
[[nodiscard]] std::string apply_contact_setting(sm::ContactDef& def, std::string_view key_value);

/// Picks the contact solver by name: "soft" (the engine's default) or "penalty" (the paper's springs).
/// Returns an empty string, or what was wrong.
[[nodiscard]] std::string apply_contact_solver(sm::ContactDef& def, std::string_view name);

/// A fixed LCG, so every run builds the same scene; uniform in [-1, 1).
struct Lcg {
    uint32_t state = 2026;
    double next()
    {
        state = state * 1664525u + 1013904223u;
        return static_cast<double>(state >> 8) / 8388608.0 - 1.0;
    }
};

[[nodiscard]] double process_cpu_seconds(); ///< CPU time of the whole process [s].
[[nodiscard]] double wall_seconds();        ///< A monotonic clock [s].
/// The CPU model (/proc/cpuinfo "model name") and the online core count, e.g. "AMD EPYC (2 cores)".
[[nodiscard]] std::string machine_name();
[[nodiscard]] std::string today(); ///< Local date, YYYY-MM-DD.

} // namespace peer
