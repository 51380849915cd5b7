// SPDX-License-Identifier: MIT
// The "constraints" block of `supermodal run`'s summary.
#pragma once

#include "supermodal/world.h"

#include <nlohmann/json.hpp>

namespace supermodal::cli
{

/// Count, broken count, final and peak max error [m], and per constraint its bodies and errors.
[[nodiscard]] nlohmann::json constraint_summary(const World& world, double peak_error);

} // namespace supermodal::cli
