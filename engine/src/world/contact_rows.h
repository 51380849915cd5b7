// SPDX-License-Identifier: MIT
// Which of a pair's contact points become soft-contact rows.
#pragma once

#include "contact/narrowphase.h"
#include "dynamics/body.h"
#include "world/components.h"

#include <cstddef>
#include <cstdint>
#include <span>

namespace supermodal
{
class Parallel;
struct ContactWorld;

// Most rows a pair takes: a sampled pair may have dozens of points on one patch, and as rigid rows
// they are nearly redundant, which Gauss–Seidel converges on slowly (measured: a sampled sphere resting
// at 1/60 s rolled at 2 mm/s on all its points). Four spanning the patch hold it flat.
constexpr size_t k_max_rows_per_pair = 4;
// ... but a deforming body is not flat under four rows: loaded at four points, its modes bend round
// them, and the order the rows are taken in shows (measured: an elastic block pressed straight down at
// its top's middle slid 0.18 mm on four rows, 0.05 mm on 32). Its modal compliance keeps many rows
// from being redundant; they spread over the patch like the samples the penalty method loads.
constexpr size_t k_max_rows_per_modal_pair = 32;

// Whether the body rests on a patch or on several tips rather than in one point.
bool rests_on_a_patch(const BodyModel& m);

// Up to out.size() (k_max_rows_per_pair, or more for a modal pair) of the points; their indices in
// `out`, the count returned. On round bodies (flat_faces false) the deepest alone.
size_t pick_rows(std::span<const ContactPoint> points, bool flat_faces, std::span<uint32_t> out);

/// The pairs that take rows (points, and a body that can move), in pair order, into SoftContacts::pairs,
/// each with its first point in SoftContacts::points (sized here); counted and written on the threads.
void gather_pairs_with_rows(const Parallel& par, const Registry& reg, ContactWorld& io);

} // namespace supermodal
