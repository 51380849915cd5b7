// SPDX-License-Identifier: MIT
#include "contact/events.h"

#include <algorithm>
#include <limits>

namespace supermodal
{
namespace
{

ContactEvent event_from(ContactEventKind kind, Entity a, Entity b, const PairTouch& t)
{
    return {.kind = kind,
            .a = a,
            .b = b,
            .point = t.point,
            .normal = t.normal,
            .impulse_on_a = t.impulse_on_a,
            .normal_impulse = t.normal_impulse,
            .depth = t.depth};
}

// An End for a pair that did not touch this step: where it last touched, no impulse.
ContactEvent end_from(const TouchRecord& r)
{
    return {.kind = ContactEventKind::End, .a = r.a, .b = r.b, .point = r.point, .normal = r.normal};
}

} // namespace

void begin_step_events(ContactEvents& io, size_t pair_count)
{
    // Only new slots are written here; the others are stale by the new step number.
    io.touch.resize(pair_count);
    ++io.step;
}

void accumulate_touch(ContactEvents& io, size_t pair_index, const ContactInfo& info, double normal_force,
                      double h)
{
    PairTouch& t = io.touch[pair_index];
    if (t.step != io.step)
        t = PairTouch{.step = io.step};
    t.touched = true;
    t.point = info.point;
    t.normal = info.normal;
    t.impulse_on_a += h * info.force_on_a;
    t.normal_impulse += h * normal_force;
    t.depth = std::max(t.depth, info.depth);
}

void publish_events(ContactEvents& io, std::span<const BodyPair> pairs, std::span<const ContactInfo> last)
{
    io.events.clear();
    io.next.clear();
    constexpr uint64_t k_none = std::numeric_limits<uint64_t>::max();
    const std::vector<TouchRecord>& prev = io.touching;
    size_t i = 0, j = 0, c = 0;
    // Merge of two key-sorted lists (last step's touching pairs, this step's candidates), so events come
    // out in key order without a sort.
    while (i < prev.size() || j < pairs.size()) {
        const uint64_t key_prev = i < prev.size() ? prev[i].key : k_none;
        const uint64_t key_pair = j < pairs.size() ? pairs[j].key() : k_none;
        if (key_prev < key_pair) { // no longer a candidate: it let go
            io.events.push_back(end_from(prev[i++]));
            continue;
        }
        const BodyPair& pair = pairs[j];
        const bool was = key_prev == key_pair;
        const bool at_end = c < last.size() && last[c].a == pair.a && last[c].b == pair.b;
        const PairTouch t = j < io.touch.size() && io.touch[j].step == io.step ? io.touch[j] : PairTouch{};
        if (t.touched) {
            // The step's impulse is reported once per pair: on its Begin or Persist, else on its End.
            if (!was)
                io.events.push_back(event_from(ContactEventKind::Begin, pair.a, pair.b, t));
            else if (at_end)
                io.events.push_back(event_from(ContactEventKind::Persist, pair.a, pair.b, t));
            if (!at_end) {
                ContactEvent end = event_from(ContactEventKind::End, pair.a, pair.b, t);
                if (!was)
                    end.impulse_on_a = {}, end.normal_impulse = 0.0;
                io.events.push_back(end);
            }
        } else if (was) {
            io.events.push_back(end_from(prev[i]));
        }
        if (at_end) {
            io.next.push_back({key_pair, pair.a, pair.b, t.point, t.normal});
            ++c;
        }
        i += was ? 1 : 0;
        ++j;
    }
    io.touching.swap(io.next);
    if (io.callback != nullptr)
        for (const ContactEvent& e : io.events)
            io.callback(e, io.user_data);
}

} // namespace supermodal
