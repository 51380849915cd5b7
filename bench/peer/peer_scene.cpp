// SPDX-License-Identifier: MIT
#include "peer/peer_scene.h"

#include "supermodal/body.h"
#include "supermodal/world.h"

#include <charconv>
#include <chrono>
#include <ctime>
#include <fstream>
#include <unistd.h>
#include <utility>

namespace peer
{

namespace
{

class SupermodalWorld final : public PeerWorld
{
  public:
    SupermodalWorld(const SceneSpec& scene, const SupermodalOptions& options)
        : m_world(world_def(scene, options))
    {
        for (const PlaneSpec& p : scene.planes) {
            sm::BodyDef d = body_def(scene);
            d.motion = sm::MotionType::Static;
            d.shape.type = sm::ShapeType::Plane;
            d.shape.plane_normal = p.normal;
            d.shape.plane_offset = p.offset;
            (void)sm::create_body(m_world, d);
        }
        for (const BodySpec& b : scene.bodies) {
            sm::BodyDef d = body_def(scene);
            d.shape = supermodal_shape(b);
            d.position = b.position;
            d.orientation = b.orientation;
            m_bodies.push_back(sm::create_body(m_world, d));
        }
    }
    void step() override { m_world.step(); }
    [[nodiscard]] double max_penetration() const override { return sm::world_max_penetration(m_world); }
    [[nodiscard]] sm::Vec3 position(int body) const override
    {
        return sm::body_position(m_world, m_bodies[static_cast<size_t>(body)]);
    }
    [[nodiscard]] double speed(int body) const override
    {
        return sm::length(sm::body_linear_velocity(m_world, m_bodies[static_cast<size_t>(body)]));
    }

  private:
    static sm::WorldDef world_def(const SceneSpec& scene, const SupermodalOptions& options)
    {
        sm::WorldDef def = sm::default_world_def();
        def.dt = scene.dt;
        def.gravity = scene.gravity;
        def.substep_count = options.substeps;
        def.contact = options.contact;
        def.thread_count = 1;
        return def;
    }
    static sm::BodyDef body_def(const SceneSpec& scene)
    {
        sm::BodyDef d = sm::default_body_def();
        d.density = scene.density;
        d.friction = scene.friction; // a pair uses √(μa·μb) = μ
        d.restitution = scene.restitution;
        return d;
    }
    sm::World m_world;
    std::vector<sm::Entity> m_bodies;
};

template <typename T> std::string parse_number(std::string_view text, T& out)
{
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    if (ec != std::errc{} || end != text.data() + text.size())
        return "not a number: '" + std::string(text) + "'";
    return {};
}

template <typename E>
std::string parse_enum(std::string_view text, E& out,
                       std::initializer_list<std::pair<std::string_view, E>> names)
{
    for (const auto& [name, value] : names)
        if (text == name) {
            out = value;
            return {};
        }
    return "unknown value '" + std::string(text) + "'";
}

} // namespace

std::string_view kind_name(Kind kind)
{
    switch (kind) {
    case Kind::Box:
        return "box";
    case Kind::Sphere:
        return "sphere";
    case Kind::Ellipsoid:
        return "ellipsoid";
    }
    return "?";
}

sm::ShapeDef supermodal_shape(const BodySpec& body)
{
    sm::ShapeDef s = sm::default_shape_def();
    s.radii = body.half;
    if (body.kind == Kind::Box)
        s.epsilon1 = s.epsilon2 = 0.3;
    return s;
}

std::unique_ptr<PeerWorld> make_supermodal_world(const SceneSpec& scene, const SupermodalOptions& options)
{
    return std::make_unique<SupermodalWorld>(scene, options);
}

namespace
{

std::string set_contact_field(sm::ContactDef& def, std::string_view key_value);

} // namespace

std::string apply_contact_setting(sm::ContactDef& def, std::string_view key_value)
{
    // Refused as the engine refuses it (exit 2 from the benches), not by an assertion in the world.
    sm::WorldDef world = sm::default_world_def();
    world.contact = def;
    if (std::string error = set_contact_field(world.contact, key_value); !error.empty())
        return error;
    if (const sm::Status ok = sm::validate(world); !ok)
        return std::string(key_value) + ": " + ok.error().message();
    def = world.contact;
    return {};
}

namespace
{

std::string set_contact_field(sm::ContactDef& def, std::string_view key_value)
{
    const size_t eq = key_value.find('=');
    if (eq == std::string_view::npos)
        return "expected key=value, got '" + std::string(key_value) + "'";
    const std::string_view key = key_value.substr(0, eq), value = key_value.substr(eq + 1);
    using P = sm::ContactPath;
    using S = sm::ContactStiffness;
    if (key == "enabled")
        return parse_enum(value, def.enabled, {{"true", true}, {"1", true}, {"false", false}, {"0", false}});
    if (key == "path")
        return parse_enum(value, def.path,
                          {{"auto", P::Auto}, {"sampling", P::Sampling}, {"support_map", P::SupportMap}});
    if (key == "stiffness")
        return parse_enum(value, def.stiffness, {{"frequency", S::Frequency}, {"material", S::Material}});
    if (key == "frequency_hz")
        return parse_number(value, def.frequency_hz);
    if (key == "damping_ratio")
        return parse_number(value, def.damping_ratio);
    if (key == "sample_spacing")
        return parse_number(value, def.sample_spacing);
    if (key == "speculative_speed_factor")
        return parse_number(value, def.speculative_speed_factor);
    if (key == "max_samples_per_body")
        return parse_number(value, def.max_samples_per_body);
    if (key == "max_auto_substeps")
        return parse_number(value, def.max_auto_substeps);
    if (key == "soft.frequency_hz")
        return parse_number(value, def.soft.frequency_hz);
    if (key == "soft.iterations")
        return parse_number(value, def.soft.iterations);
    if (key == "soft.relax_iterations")
        return parse_number(value, def.soft.relax_iterations);
    if (key == "soft.substeps")
        return parse_number(value, def.soft.substeps);
    if (key == "soft.damping_ratio")
        return parse_number(value, def.soft.damping_ratio);
    if (key == "soft.push_out_speed")
        return parse_number(value, def.soft.push_out_speed);
    return "unknown contact setting '" + std::string(key) + "'";
}

} // namespace

std::string apply_contact_solver(sm::ContactDef& def, std::string_view name)
{
    if (name == "penalty") {
        def.solver = sm::ContactSolver::Penalty;
        return {};
    }
    if (name == "soft") {
        def.solver = sm::ContactSolver::Soft;
        return {};
    }
    return "unknown contact solver '" + std::string(name) + "' (expected penalty or soft)";
}

double process_cpu_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wall_seconds()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string machine_name()
{
    std::ifstream in("/proc/cpuinfo");
    std::string line, model = "unknown CPU";
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    return model + " (" + std::to_string(sysconf(_SC_NPROCESSORS_ONLN)) + " cores)";
}

std::string today()
{
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char text[16];
    std::strftime(text, sizeof text, "%Y-%m-%d", &local);
    return text;
}

} // namespace peer
