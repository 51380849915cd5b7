// SPDX-License-Identifier: MIT
#include "scene/constraint_reader.h"

#include "scene/body_reader.h"

#include <cmath>

namespace supermodal::scene_io
{
namespace
{

const std::vector<std::string_view> k_constraint_keys = {"name",
                                                         "type",
                                                         "a",
                                                         "b",
                                                         "anchor_a",
                                                         "anchor_b",
                                                         "frequency",
                                                         "damping_ratio",
                                                         "rest_length",
                                                         "swing_limit",
                                                         "twist_limit",
                                                         "axis_a",
                                                         "break_force",
                                                         "collide_connected",
                                                         "angular_damping"};
const std::vector<std::string_view> k_constraint_types = {"point", "distance", "weld"};
const std::vector<std::string_view> k_anchor_keys = {"point", "direction", "surface"};

// An anchor is [x, y, z] (a point in the body's shape frame) or an object with exactly one of
// "point", "direction" or "surface": [eta, omega].
void read_anchor(Reader& r, const Json& value, const std::string& where, AnchorDef& out)
{
    if (value.is_array())
        return r.read_vec3(value, where, any_number(), out.point);
    if (!value.is_object())
        return r.fail(where,
                      "expected [x, y, z] or an object with \"point\", \"direction\" or \"surface\", found " +
                          describe_value(value));
    if (!r.check_object(value, where, k_anchor_keys))
        return;
    int kinds = 0;
    if (const Json* p = r.member(value, "point")) {
        r.read_vec3(*p, pointer_join(where, "point"), any_number(), out.point);
        out.kind = AnchorKind::Point;
        ++kinds;
    }
    if (const Json* d = r.member(value, "direction")) {
        r.read_vec3(*d, pointer_join(where, "direction"), any_number(), out.direction);
        if (r.ok() && !(length(out.direction) > 0.0))
            return r.fail(pointer_join(where, "direction"), "expected a non-zero direction, found [0, 0, 0]");
        out.kind = AnchorKind::Direction;
        ++kinds;
    }
    if (const Json* s = r.member(value, "surface")) {
        double angles[2] = {0.0, 0.0};
        r.read_numbers(*s, pointer_join(where, "surface"), closed(-M_PI, M_PI), angles);
        if (r.ok() && std::abs(angles[0]) > 0.5 * M_PI)
            return r.fail(pointer_join(pointer_join(where, "surface"), size_t{0}),
                          "expected a latitude eta in [-pi/2, pi/2] rad, found " + format_number(angles[0]));
        out.eta = angles[0];
        out.omega = angles[1];
        out.kind = AnchorKind::Surface;
        ++kinds;
    }
    if (r.ok() && kinds != 1)
        r.fail(where, "expected exactly one of \"point\", \"direction\" or \"surface\"");
}

void read_constraint(Reader& r, const Json& value, const std::string& where, const Scene& scene,
                     SceneConstraint& out)
{
    if (!r.check_object(value, where, k_constraint_keys))
        return;
    ConstraintDef& d = out.def;
    if (const Json* name = r.member(value, "name"))
        r.read_string(*name, pointer_join(where, "name"), d.name);
    if (const Json* type = r.require(value, where, "type")) {
        size_t index = 0;
        r.read_choice(*type, pointer_join(where, "type"), k_constraint_types, index);
        d.type = static_cast<ConstraintType>(index);
    }
    if (const Json* a = r.require(value, where, "a"))
        read_body_name(r, *a, pointer_join(where, "a"), scene, out.body_a, "no body named");
    if (const Json* b = r.member(value, "b"); b != nullptr && !(b->is_string() && *b == "world"))
        read_body_name(r, *b, pointer_join(where, "b"), scene, out.body_b, "no body named");
    if (r.ok() && out.body_a == out.body_b)
        return r.fail(pointer_join(where, "b"),
                      "a constraint needs two different bodies, found " + quote_text(out.body_b) + " twice");
    if (const Json* anchor = r.member(value, "anchor_a"))
        read_anchor(r, *anchor, pointer_join(where, "anchor_a"), d.anchor_a);
    if (const Json* anchor = r.member(value, "anchor_b"))
        read_anchor(r, *anchor, pointer_join(where, "anchor_b"), d.anchor_b);
    if (r.ok() && out.body_b.empty() && d.anchor_b.kind != AnchorKind::Point)
        return r.fail(pointer_join(where, "anchor_b"), "an anchor in the world must be a point [x, y, z]");
    r.field_number(value, where, "frequency", above(0.0), d.frequency_hz);
    r.field_number(value, where, "damping_ratio", at_least(0.0), d.damping_ratio);
    r.field_number(value, where, "rest_length", at_least(0.0), d.rest_length);
    r.field_number(value, where, "swing_limit", closed(0.0, M_PI), d.swing_limit);
    r.field_number(value, where, "twist_limit", closed(0.0, M_PI), d.twist_limit);
    r.field_vec3(value, where, "axis_a", any_number(), d.axis_a);
    r.field_number(value, where, "break_force", above(0.0), d.break_force);
    r.field_number(value, where, "angular_damping", at_least(0.0), d.angular_damping);
    if (const Json* cc = r.member(value, "collide_connected")) {
        if (!cc->is_boolean())
            return r.fail(pointer_join(where, "collide_connected"),
                          "expected true or false, found " + describe_value(*cc));
        d.collide_connected = cc->get<bool>();
    }
    if (r.ok() && (d.type != ConstraintType::Point) && (d.swing_limit >= 0.0 || d.twist_limit >= 0.0))
        r.fail(where, "swing_limit and twist_limit apply to \"point\" constraints only");
}

} // namespace

void read_constraints(Reader& r, const Json& root, Scene& out_scene)
{
    const Json* constraints = r.member(root, "constraints");
    if (constraints == nullptr)
        return;
    if (!constraints->is_array())
        return r.fail("/constraints", "expected an array, found " + describe_value(*constraints));
    for (size_t i = 0; i < constraints->size() && r.ok(); ++i) {
        SceneConstraint c;
        c.def = default_constraint_def();
        read_constraint(r, (*constraints)[i], pointer_join("/constraints", i), out_scene, c);
        if (r.ok())
            out_scene.constraints.push_back(std::move(c));
    }
}

} // namespace supermodal::scene_io
