// SPDX-License-Identifier: MIT
#include "peer/bullet_world.h"

#include <algorithm>
#include <btBulletDynamicsCommon.h>
#include <cmath>
#include <utility>
#include <vector>

namespace peer
{

namespace
{

btVector3 to_bt(const sm::Vec3& v)
{
    return {static_cast<btScalar>(v.x), static_cast<btScalar>(v.y), static_cast<btScalar>(v.z)};
}

btQuaternion to_bt(const sm::Quat& q)
{
    return {static_cast<btScalar>(q.x), static_cast<btScalar>(q.y), static_cast<btScalar>(q.z),
            static_cast<btScalar>(q.w)};
}

class BulletWorld final : public PeerWorld
{
  public:
    BulletWorld(const SceneSpec& scene, const BulletOptions& options)
        : m_options(options), m_dt(static_cast<btScalar>(scene.dt))
    {
        m_world.setGravity(to_bt(scene.gravity));
        // Bullet multiplies the two coefficients of a pair: √μ on each body gives the pair μ, as
        // supermodal's √(μa·μb) does with μ on each.
        const auto friction = static_cast<btScalar>(std::sqrt(scene.friction));
        const auto restitution = static_cast<btScalar>(scene.restitution);
        for (const PlaneSpec& p : scene.planes) {
            m_shapes.push_back(
                std::make_unique<btStaticPlaneShape>(to_bt(p.normal), static_cast<btScalar>(p.offset)));
            add_body(*m_shapes.back(), 0.0, btVector3(0, 0, 0), btTransform::getIdentity(), friction,
                     restitution);
        }
        for (const BodySpec& b : scene.bodies) {
            // The mass and inertia of supermodal's shape, so that only the contact differs.
            const sm::MassProperties mp = sm::compute_mass_properties(supermodal_shape(b), scene.density);
            add_body(shape_for(b), mp.mass, to_bt(mp.inertia_diagonal),
                     btTransform(to_bt(b.orientation), to_bt(b.position)), friction, restitution);
        }
        m_first_dynamic = scene.planes.size();
    }
    ~BulletWorld() override
    {
        for (auto& body : m_bodies)
            m_world.removeRigidBody(body.get());
    }
    BulletWorld(const BulletWorld&) = delete;
    BulletWorld& operator=(const BulletWorld&) = delete;

    // One internal step of dt: fixed step dt, at most one substep.
    void step() override { m_world.stepSimulation(m_dt, 1, m_dt); }
    [[nodiscard]] double max_penetration() const override
    {
        // Contact points keep their signed distance (negative: overlap), refreshed every step.
        double deepest = 0.0;
        const btCollisionDispatcher& d = m_dispatcher;
        for (int i = 0; i < d.getNumManifolds(); ++i) {
            const btPersistentManifold& m = *d.getManifoldByIndexInternal(i);
            for (int j = 0; j < m.getNumContacts(); ++j)
                deepest = std::max(deepest, -static_cast<double>(m.getContactPoint(j).getDistance()));
        }
        return deepest;
    }
    [[nodiscard]] sm::Vec3 position(int body) const override
    {
        const btVector3& p = dynamic(body).getCenterOfMassPosition();
        return {p.x(), p.y(), p.z()};
    }
    [[nodiscard]] double speed(int body) const override { return dynamic(body).getLinearVelocity().length(); }

  private:
    [[nodiscard]] const btRigidBody& dynamic(int body) const
    {
        return *m_bodies[m_first_dynamic + static_cast<size_t>(body)];
    }
    btCollisionShape& shape_for(const BodySpec& b);
    void add_body(btCollisionShape& shape, double mass, const btVector3& inertia, const btTransform& pose,
                  btScalar friction, btScalar restitution)
    {
        btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), nullptr, &shape, inertia);
        info.m_startWorldTransform = pose;
        info.m_friction = friction;
        info.m_restitution = restitution;
        m_bodies.push_back(std::make_unique<btRigidBody>(info));
        if (mass > 0.0 && !m_options.deactivation)
            m_bodies.back()->setActivationState(DISABLE_DEACTIVATION);
        m_world.addRigidBody(m_bodies.back().get());
    }

    BulletOptions m_options;
    btScalar m_dt;
    // Declared in the order they depend on each other: destroyed world first, configuration last.
    btDefaultCollisionConfiguration m_config;
    btCollisionDispatcher m_dispatcher{&m_config};
    btDbvtBroadphase m_broadphase;
    btSequentialImpulseConstraintSolver m_solver;
    btDiscreteDynamicsWorld m_world{&m_dispatcher, &m_broadphase, &m_solver, &m_config};
    std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
    std::vector<std::pair<BodySpec, btCollisionShape*>> m_shape_of; // shared by equal kind and size
    std::vector<std::unique_ptr<btRigidBody>> m_bodies;             // planes first, then dynamic bodies
    size_t m_first_dynamic = 0;
};

btCollisionShape& BulletWorld::shape_for(const BodySpec& b)
{
    for (const auto& [spec, shape] : m_shape_of)
        if (spec.kind == b.kind && spec.half == b.half)
            return *shape;
    const btVector3 half = to_bt(b.half);
    std::unique_ptr<btCollisionShape> shape;
    if (b.kind == Kind::Box) {
        shape = std::make_unique<btBoxShape>(half);
        shape->setMargin(static_cast<btScalar>(m_options.margin)); // keeps the outer half extents
    } else if (b.kind == Kind::Sphere) {
        shape = std::make_unique<btSphereShape>(half.x()); // its margin is its radius
    } else {
        // The usual ellipsoid in Bullet: a unit sphere scaled per axis. Margin first: the scaling
        // recomputes the cached bounds.
        const btVector3 centre(0, 0, 0);
        const btScalar radius = 1;
        shape = std::make_unique<btMultiSphereShape>(&centre, &radius, 1);
        shape->setMargin(static_cast<btScalar>(m_options.margin));
        shape->setLocalScaling(half);
    }
    m_shape_of.emplace_back(b, shape.get());
    m_shapes.push_back(std::move(shape));
    return *m_shapes.back();
}

} // namespace

std::unique_ptr<PeerWorld> make_bullet_world(const SceneSpec& scene, const BulletOptions& options)
{
    return std::make_unique<BulletWorld>(scene, options);
}

std::string bullet_name()
{
    const int v = btGetVersion();
    return "Bullet " + std::to_string(v / 100) + "." + std::to_string(v % 100) +
           (sizeof(btScalar) == 8 ? " (double)" : " (float)");
}

} // namespace peer
