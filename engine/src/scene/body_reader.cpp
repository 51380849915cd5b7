// SPDX-License-Identifier: MIT
#include "scene/body_reader.h"

#include "geometry/hyperquadric_solve.h"
#include "modal/lattice.h"
#include "scene/did_you_mean.h"
#include "supermodal/modal.h"
#include "supermodal/shape.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>

namespace supermodal::scene_io
{
namespace
{

const std::vector<std::string_view> k_body_keys = {"name",        "shape",         "material",
                                                   "density",     "mass",          "position",
                                                   "orientation", "velocity",      "angular_velocity",
                                                   "motion",      "gravity_scale", "dynamics",
                                                   "parent",      "mesh",          "sleep"};
// In ShapeType order, so a choice's index is its enumerator; each type's keys at the same index.
const std::vector<std::string_view> k_shape_types = {"superquadric", "plane", "hyperquadric"};
const std::vector<std::vector<std::string_view>> k_shape_keys = {
    {"type", "radii", "exponents", "taper", "bend"}, {"type", "normal", "offset"}, {"type", "terms"}};
static_assert(static_cast<int>(ShapeType::Plane) == 1 && static_cast<int>(ShapeType::Hyperquadric) == 2);
const std::vector<std::string_view> k_term_keys = {"normal", "offset", "exponent"};
const std::vector<std::string_view> k_bend_keys = {"curvature", "angle"};
const std::vector<std::string_view> k_dynamics_keys = {"type",       "modes",         "lattice",
                                                       "integrator", "damping_ratio", "static_correction"};
// In ModalIntegrator order, so a choice's index is its enumerator.
const std::vector<std::string_view> k_integrator_names = {"exact", "central_difference"};
static_assert(static_cast<int>(ModalIntegrator::Exact) == 0 &&
              static_cast<int>(ModalIntegrator::CentralDifference) == 1);
// Both lists are in enum order, so a choice's index is its enumerator.
const std::vector<std::string_view> k_motion_names = {"static", "kinematic", "dynamic"};
const std::vector<std::string_view> k_dynamics_types = {"rigid", "modal", "auto", "full"};
static_assert(static_cast<int>(MotionType::Static) == 0 && static_cast<int>(MotionType::Dynamic) == 2);
static_assert(static_cast<int>(DynamicsType::Rigid) == 0 && static_cast<int>(DynamicsType::Auto) == 2 &&
              static_cast<int>(DynamicsType::Full) == 3);

/// Superquadric exponents ε1, ε2: (0, 4]; ε → 0 tends to a box (0 itself divides by zero in the
/// inside-outside function) and past 2 the body is concave.
const Range k_exponent_range{.min = 0.0, .max = 4.0, .min_open = true};
/// Barr taper factors: past ±1 the cross-section would shrink through zero inside the body.
const Range k_taper_range = closed(-1.0, 1.0);
/// Fewer than three terms cannot bound a 3-D body (their normals span at most a plane).
constexpr size_t k_min_terms = 3;
/// Every evaluation of H sums all terms; past this a scene is more likely broken than meant.
constexpr size_t k_max_terms = 256;

/// Material lookup for bodies: name → index into Scene::materials, plus the names in file order.
struct MaterialIndex {
    std::map<std::string, size_t, std::less<>> by_name;
    std::vector<std::string_view> names;
};

/// |Σc² − 1| up to which a vector counts as unit already [-]: a few roundings of a normalised vector.
constexpr double k_unit_tolerance = 8.0 * std::numeric_limits<double>::epsilon();

/// Scales by the largest component before normalising, so [1e-200, 0, 0] still gives a unit vector;
/// false when every component is zero. A vector that is unit to rounding is kept bit for bit, so a
/// scene written by save_scene() reads back identical (normalising again would move the last bits).
template <size_t N> bool normalize_components(double (&c)[N])
{
    double sum_squares = 0.0;
    for (double v : c)
        sum_squares += v * v;
    if (std::abs(sum_squares - 1.0) <= k_unit_tolerance)
        return true;
    double largest = 0.0;
    for (double v : c)
        largest = std::max(largest, std::abs(v));
    if (largest == 0.0)
        return false;
    double sum = 0.0;
    for (double& v : c) {
        v /= largest;
        sum += v * v;
    }
    const double n = std::sqrt(sum);
    for (double& v : c)
        v /= n;
    return true;
}

/// Keys of another shape type get a clearer message than "unknown key".
void check_shape_keys(Reader& r, const Json& shape, const std::string& where, ShapeType type)
{
    const size_t own_index = static_cast<size_t>(type);
    const auto& own = k_shape_keys[own_index];
    for (const auto& item : shape.items()) {
        const std::string& key = item.key();
        if (std::find(own.begin(), own.end(), key) != own.end())
            continue;
        for (size_t other = 0; other < k_shape_keys.size(); ++other)
            if (other != own_index && std::find(k_shape_keys[other].begin(), k_shape_keys[other].end(),
                                                key) != k_shape_keys[other].end()) {
                r.fail(pointer_join(where, key), quote_text(key) + " does not apply to a " +
                                                     std::string(k_shape_types[own_index]) +
                                                     "; its keys are " + join_names(own));
                return;
            }
    }
    r.check_object(shape, where, own);
}

void read_superquadric(Reader& r, const Json& shape, const std::string& where, ShapeDef& out_shape)
{
    if (const Json* radii = r.require(shape, where, "radii"))
        r.read_vec3(*radii, pointer_join(where, "radii"), above(0.0), out_shape.radii);
    if (const Json* exponents = r.member(shape, "exponents")) {
        double e[2] = {out_shape.epsilon1, out_shape.epsilon2};
        r.read_numbers(*exponents, pointer_join(where, "exponents"), k_exponent_range, e);
        out_shape.epsilon1 = e[0];
        out_shape.epsilon2 = e[1];
    }
    if (const Json* taper = r.member(shape, "taper")) {
        double k[2] = {out_shape.taper.kx, out_shape.taper.ky};
        r.read_numbers(*taper, pointer_join(where, "taper"), k_taper_range, k);
        out_shape.taper = {k[0], k[1]};
    }
    if (const Json* bend = r.member(shape, "bend")) {
        const std::string bend_where = pointer_join(where, "bend");
        if (r.check_object(*bend, bend_where, k_bend_keys)) {
            r.field_number(*bend, bend_where, "curvature", at_least(0.0), out_shape.bend.curvature);
            r.field_number(*bend, bend_where, "angle", any_number(), out_shape.bend.angle);
        }
    }
}

void read_plane(Reader& r, const Json& shape, const std::string& where, ShapeDef& out_shape)
{
    if (const Json* normal = r.member(shape, "normal")) {
        const std::string normal_where = pointer_join(where, "normal");
        r.read_vec3(*normal, normal_where, any_number(), out_shape.plane_normal);
        double n[3] = {out_shape.plane_normal.x, out_shape.plane_normal.y, out_shape.plane_normal.z};
        if (r.ok() && !normalize_components(n))
            r.fail(normal_where, "plane normal has zero length");
        out_shape.plane_normal = {n[0], n[1], n[2]};
    }
    r.field_number(shape, where, "offset", any_number(), out_shape.plane_offset);
}

void read_term(Reader& r, const Json& term, const std::string& where, HyperquadricTerm& out_term)
{
    if (!r.check_object(term, where, k_term_keys))
        return;
    if (const Json* normal = r.require(term, where, "normal")) {
        r.read_vec3(*normal, pointer_join(where, "normal"), any_number(), out_term.normal);
        if (r.ok() && out_term.normal == Vec3{})
            r.fail(pointer_join(where, "normal"), "term normal has zero length");
    }
    r.field_number(term, where, "offset", any_number(), out_term.offset);
    if (const Json* exponent = r.require(term, where, "exponent"))
        r.read_number(*exponent, pointer_join(where, "exponent"), above(0.0), out_term.exponent);
}

void read_hyperquadric(Reader& r, const Json& shape, const std::string& where, ShapeDef& out_shape)
{
    const Json* terms = r.require(shape, where, "terms");
    if (terms == nullptr)
        return;
    const std::string terms_where = pointer_join(where, "terms");
    if (!terms->is_array() || terms->size() < k_min_terms || terms->size() > k_max_terms)
        return r.fail(terms_where, "expected an array of " + std::to_string(k_min_terms) + " to " +
                                       std::to_string(k_max_terms) +
                                       " terms {\"normal\", \"offset\", \"exponent\"}, found " +
                                       describe_value(*terms));
    out_shape.terms.resize(terms->size());
    for (size_t i = 0; i < terms->size(); ++i)
        read_term(r, (*terms)[i], pointer_join(terms_where, i), out_shape.terms[i]);
    if (!r.ok())
        return;
    const HyperquadricCenter center = hyperquadric_center(out_shape);
    if (!center.is_bounded)
        return r.fail(terms_where,
                      "the term normals do not span 3-D (they lie in one plane or along one line), "
                      "so the body would be unbounded; add a term whose normal leaves that plane");
    if (!center.is_non_empty)
        r.fail(terms_where, "the terms leave no inside: H >= 1 everywhere (smallest H found: " +
                                format_number(std::exp(center.log_value)) + "); reduce the offsets");
}

void read_shape(Reader& r, const Json& shape, const std::string& where, ShapeDef& out_shape)
{
    if (!r.ok())
        return;
    if (!shape.is_object())
        return r.fail(where, "expected an object, found " + describe_value(shape));
    size_t type = 0;
    if (const Json* type_value = r.require(shape, where, "type"))
        r.read_choice(*type_value, pointer_join(where, "type"), k_shape_types, type);
    if (!r.ok())
        return;
    out_shape = default_shape_def();
    out_shape.type = static_cast<ShapeType>(type);
    check_shape_keys(r, shape, where, out_shape.type);
    if (out_shape.type == ShapeType::Superquadric)
        read_superquadric(r, shape, where, out_shape);
    else if (out_shape.type == ShapeType::Plane)
        read_plane(r, shape, where, out_shape);
    else
        read_hyperquadric(r, shape, where, out_shape);
}

/// Density from, in order of precedence: the body's "mass" (over the shape's volume), the body's
/// "density", the body's material, the default material.
void read_density(Reader& r, const Json& body, const std::string& where, const Scene& scene,
                  const MaterialIndex& materials, SceneBody& out_body)
{
    double density = MaterialDef{}.density;
    if (const Json* material = r.member(body, "material")) {
        const std::string material_where = pointer_join(where, "material");
        r.read_string(*material, material_where, out_body.material);
        if (!r.ok())
            return;
        const auto it = materials.by_name.find(out_body.material);
        if (it != materials.by_name.end()) {
            density = scene.materials[it->second].density;
        } else {
            const std::string hint = did_you_mean(out_body.material, materials.names);
            r.fail(material_where,
                   "unknown material " + quote_text(out_body.material) + (hint.empty() ? "; " : hint + " ") +
                       (materials.names.empty() ? "the scene defines no materials"
                                                : "materials are: " + join_names(materials.names)));
            return;
        }
    }
    const Json* density_value = r.member(body, "density");
    const Json* mass_value = r.member(body, "mass");
    if (density_value != nullptr)
        r.read_number(*density_value, pointer_join(where, "density"), above(0.0), density);
    if (mass_value != nullptr) {
        const std::string mass_where = pointer_join(where, "mass");
        if (density_value != nullptr)
            return r.fail(mass_where, "give either \"density\" or \"mass\", not both");
        if (out_body.def.shape.type == ShapeType::Plane)
            return r.fail(mass_where,
                          "\"mass\" applies only to superquadrics and hyperquadrics (a plane is static)");
        double mass = 0.0;
        r.read_number(*mass_value, mass_where, above(0.0), mass);
        if (!r.ok())
            return;
        // Closed form for plain superquadrics; quadrature for tapered, bent and hyperquadric shapes.
        const double volume = compute_mass_properties(out_body.def.shape, 1.0).volume;
        density = mass / volume;
        if (!(std::isfinite(density) && density > 0.0))
            return r.fail(mass_where, "a mass of " + format_number(mass) + " kg in a volume of " +
                                          format_number(volume) + " m^3 gives no finite density > 0");
    }
    out_body.def.density = density;
}

void read_orientation(Reader& r, const Json& body, const std::string& where, Quat& out_orientation)
{
    const Json* value = r.member(body, "orientation");
    if (value == nullptr)
        return;
    const std::string orientation_where = pointer_join(where, "orientation");
    double q[4] = {1.0, 0.0, 0.0, 0.0};
    r.read_numbers(*value, orientation_where, any_number(), q);
    if (!r.ok())
        return;
    if (!normalize_components(q))
        return r.fail(orientation_where, "orientation quaternion has zero length");
    out_orientation = {q[0], q[1], q[2], q[3]};
}

/// The material a body names (already checked by read_density), or the default material.
MaterialDef material_of(const Scene& scene, const MaterialIndex& materials, const SceneBody& body)
{
    const auto it = materials.by_name.find(body.material);
    return it != materials.by_name.end() ? scene.materials[it->second] : MaterialDef{};
}

void read_dynamics(Reader& r, const Json& body, const std::string& where, const Scene& scene,
                   const MaterialIndex& materials, SceneBody& out_body)
{
    const Json* dynamics = r.member(body, "dynamics");
    if (dynamics == nullptr)
        return;
    const std::string dynamics_where = pointer_join(where, "dynamics");
    if (!r.check_object(*dynamics, dynamics_where, k_dynamics_keys))
        return;
    size_t type = 0;
    if (const Json* type_value = r.member(*dynamics, "type"))
        r.read_choice(*type_value, pointer_join(dynamics_where, "type"), k_dynamics_types, type);
    // Plasticity and the damping ratio come from the material (as do Young's modulus and Poisson's
    // ratio, on BodyDef); the body's own "damping_ratio" wins over the material's.
    const MaterialDef material = material_of(scene, materials, out_body);
    out_body.def.young = material.young;
    out_body.def.poisson = material.poisson;
    ModalBodyDef& modal = out_body.def.modal;
    modal.damping_ratio = material.damping_ratio;
    modal.yield_stress = material.yield_stress;
    modal.hardening = material.hardening;
    modal.max_plastic_strain = material.max_plastic_strain;
    modal.remould_threshold = material.remould_threshold;
    r.field_int(*dynamics, dynamics_where, "modes", closed(1.0, k_max_modes), modal.mode_count);
    if (const Json* lattice = r.member(*dynamics, "lattice")) {
        const std::string lattice_where = pointer_join(dynamics_where, "lattice");
        if (!lattice->is_array() || lattice->size() != 3)
            return r.fail(lattice_where, "expected an array of 3 integers in [1, " +
                                             std::to_string(k_max_lattice_cells) + "], found " +
                                             describe_value(*lattice));
        for (size_t i = 0; i < 3; ++i)
            r.read_int((*lattice)[i], pointer_join(lattice_where, i), closed(1.0, k_max_lattice_cells),
                       modal.lattice[i]);
        // Refused here, before any world would start building it (scene lattices are 20-node).
        if (r.ok() && modal::lattice_dof_bound(modal.lattice, 2) > k_max_lattice_dofs)
            return r.fail(lattice_where, "expected a lattice of at most " +
                                             std::to_string(k_max_lattice_dofs) +
                                             " degrees of freedom, found " +
                                             std::to_string(modal::lattice_dof_bound(modal.lattice, 2)));
    }
    if (const Json* integrator = r.member(*dynamics, "integrator")) {
        size_t index = 0;
        r.read_choice(*integrator, pointer_join(dynamics_where, "integrator"), k_integrator_names, index);
        modal.integrator = static_cast<ModalIntegrator>(index);
    }
    r.field_number(*dynamics, dynamics_where, "damping_ratio", at_least(0.0), modal.damping_ratio);
    r.field_bool(*dynamics, dynamics_where, "static_correction", modal.static_correction);
    if (!r.ok())
        return;
    out_body.dynamics = static_cast<DynamicsType>(type);
    const std::string type_where = pointer_join(dynamics_where, "type");
    if (out_body.dynamics == DynamicsType::Auto) {
        // Modal with adaptive modes where the body can deform; rigid where it cannot.
        const ShapeType shape = out_body.def.shape.type;
        modal.enabled = out_body.def.motion == MotionType::Dynamic &&
                        (shape == ShapeType::Superquadric || shape == ShapeType::Hyperquadric);
        modal.adaptive_tolerance = modal.enabled ? scene.accuracy.displacement : 0.0;
        return;
    }
    if (out_body.dynamics == DynamicsType::Full) {
        if (r.member(*dynamics, "modes") != nullptr)
            return r.fail(
                pointer_join(dynamics_where, "modes"),
                "a \"full\" body keeps every mode of its lattice: leave \"modes\" out (or use \"modal\")");
        modal.mode_count = k_all_modes;
    }
    modal.enabled = out_body.dynamics == DynamicsType::Modal || out_body.dynamics == DynamicsType::Full;
    if (modal.enabled && out_body.def.motion != MotionType::Dynamic)
        r.fail(type_where, "modal dynamics need a \"dynamic\" body, found motion " +
                               quote_text(k_motion_names[static_cast<size_t>(out_body.def.motion)]));
}

void read_body(Reader& r, const Json& body, const std::string& where, const Scene& scene,
               const MaterialIndex& materials, SceneBody& out_body)
{
    if (!r.check_object(body, where, k_body_keys))
        return;
    BodyDef& def = out_body.def;
    if (const Json* name = r.require(body, where, "name")) {
        r.read_string(*name, pointer_join(where, "name"), def.name);
        if (r.ok() && def.name.empty())
            r.fail(pointer_join(where, "name"), "expected a non-empty name, found an empty string");
    }
    if (const Json* shape = r.require(body, where, "shape"))
        read_shape(r, *shape, pointer_join(where, "shape"), def.shape);
    const bool is_plane = def.shape.type == ShapeType::Plane;
    // A plane can only be static, so that is its default; spelling out anything else is an error.
    def.motion = is_plane ? MotionType::Static : MotionType::Dynamic;
    if (const Json* motion = r.member(body, "motion")) {
        size_t index = static_cast<size_t>(def.motion);
        r.read_choice(*motion, pointer_join(where, "motion"), k_motion_names, index);
        def.motion = static_cast<MotionType>(index);
        if (r.ok() && is_plane && def.motion != MotionType::Static)
            r.fail(pointer_join(where, "motion"),
                   "a plane must be \"static\", found " + quote_text(k_motion_names[index]));
    }
    read_density(r, body, where, scene, materials, out_body);
    r.field_vec3(body, where, "position", any_number(), def.position);
    read_orientation(r, body, where, def.orientation);
    r.field_vec3(body, where, "velocity", any_number(), def.linear_velocity);
    r.field_vec3(body, where, "angular_velocity", any_number(), def.angular_velocity);
    r.field_number(body, where, "gravity_scale", any_number(), def.gravity_scale);
    r.field_bool(body, where, "sleep", def.allow_sleep);
    if (const Json* parent = r.member(body, "parent"))
        // An earlier body: the child's pose is read in the parent's frame.
        read_body_name(r, *parent, pointer_join(where, "parent"), scene, out_body.parent,
                       "no earlier body named", " (a parent is listed before its children)");
    read_dynamics(r, body, where, scene, materials, out_body);
    // The file is read by the loader, which knows the scene's folder (load_render_meshes).
    if (const Json* mesh = r.member(body, "mesh")) {
        r.read_string(*mesh, pointer_join(where, "mesh"), out_body.mesh);
        if (r.ok() && (out_body.mesh.empty() || is_plane))
            r.fail(pointer_join(where, "mesh"),
                   is_plane ? "a plane has no render mesh" : "expected a file name, found an empty string");
    }
}

} // namespace

void read_body_name(Reader& r, const Json& value, const std::string& where, const Scene& scene,
                    std::string& out_name, std::string_view missing, std::string_view note)
{
    r.read_string(value, where, out_name);
    if (!r.ok())
        return;
    std::vector<std::string_view> names;
    for (const SceneBody& b : scene.bodies) {
        if (b.def.name == out_name)
            return;
        names.push_back(b.def.name);
    }
    r.fail(where, std::string(missing) + " " + quote_text(out_name) + std::string(note) +
                      did_you_mean(out_name, names));
}

void read_bodies(Reader& reader, const Json& root, Scene& out_scene)
{
    const Json* bodies = reader.member(root, "bodies");
    if (bodies == nullptr)
        return;
    if (!bodies->is_array())
        return reader.fail("/bodies", "expected an array, found " + describe_value(*bodies));
    MaterialIndex materials;
    for (size_t i = 0; i < out_scene.materials.size(); ++i) {
        materials.by_name.emplace(out_scene.materials[i].name, i);
        materials.names.push_back(out_scene.materials[i].name);
    }
    std::map<std::string, size_t, std::less<>> first_with_name;
    out_scene.bodies.reserve(bodies->size());
    for (size_t i = 0; i < bodies->size() && reader.ok(); ++i) {
        const std::string where = pointer_join("/bodies", i);
        SceneBody body;
        body.def = default_body_def();
        read_body(reader, (*bodies)[i], where, out_scene, materials, body);
        if (!reader.ok())
            return;
        const auto [it, inserted] = first_with_name.emplace(body.def.name, i);
        if (!inserted)
            return reader.fail(pointer_join(where, "name"), "duplicate body name " +
                                                                quote_text(body.def.name) + " (first at " +
                                                                pointer_join("/bodies", it->second) + ")");
        // Every rule validate() knows is checked above with a precise pointer; this only catches drift.
        if (Status status = validate(body.def); !status)
            return reader.fail(where, "invalid body: " + status.error().message());
        out_scene.bodies.push_back(std::move(body));
    }
}

} // namespace supermodal::scene_io
