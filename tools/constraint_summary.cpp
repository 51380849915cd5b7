// SPDX-License-Identifier: MIT
#include "constraint_summary.h"

#include "supermodal/body.h"
#include "supermodal/constraint.h"

namespace supermodal::cli
{

nlohmann::json constraint_summary(const World& world, double peak_error)
{
    nlohmann::json list = nlohmann::json::array();
    for (Constraint c : world_constraints(world)) {
        const ConstraintDef& d = constraint_def(world, c);
        const ConstraintError e = constraint_error(world, c);
        list.push_back({{"name", d.name},
                        {"a", body_name(world, d.a)},
                        {"b", d.b.is_null() ? std::string("world") : body_name(world, d.b)},
                        {"linear_error_m", e.linear},
                        {"angular_error_rad", e.angular},
                        {"broken", constraint_broken(world, c)}});
    }
    return {{"count", list.size()},
            {"broken", world_broken_constraints(world)},
            {"max_error_m", world_max_constraint_error(world)},
            {"peak_error_m", peak_error},
            {"list", list}};
}

} // namespace supermodal::cli
