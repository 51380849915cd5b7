// SPDX-License-Identifier: MIT
// Hash, snapshot and restore: three visitors of the one list of state fields in world/state_visit.h.
#include "core/assert.h"
#include "supermodal/world.h"
#include "world/modal_system.h"
#include "world/remould.h"
#include "world/state_visit.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace supermodal
{
namespace
{

// FNV-1a, 64 bit (Fowler–Noll–Vo): offset basis and prime from the reference definition.
constexpr uint64_t k_fnv_offset = 14695981039346656037ull;
constexpr uint64_t k_fnv_prime = 1099511628211ull;
constexpr char k_magic[4] = {'S', 'M', 'S', 'S'};
constexpr size_t k_header_bytes = 8;

// The hash and the snapshot writer read the state alike, one 8-byte word per field; only where the word
// goes differs (the Sink).
template <class Sink> struct Emitter {
    Sink sink;
    void real(const double& x, Field f) { sink.word(&x, f); }
    template <class T> void integer(const T& x, Field f)
    {
        const auto u = static_cast<uint64_t>(x);
        sink.word(&u, f);
    }
    void flag(const bool& b, Field f) { real(b ? 1.0 : 0.0, f); }
    bool check(bool, const char*) { return true; }
    template <class C> const C& sequence(const C& c, Field f)
    {
        integer(c.size(), f);
        return c;
    }
};

// The hash: FNV-1a over the Hashed fields' bytes, in visit order.
struct FnvSink {
    uint64_t h = k_fnv_offset;
    void word(const void* data, Field f)
    {
        if (f != Field::Hashed)
            return;
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < 8; ++i) {
            h ^= p[i];
            h *= k_fnv_prime;
        }
    }
};

// The snapshot: every field.
struct ByteSink {
    std::vector<std::byte>& out;
    void word(const void* data, Field)
    {
        const auto* b = static_cast<const std::byte*>(data);
        out.insert(out.end(), b, b + 8);
    }
};

// The restore reader: reads the words back in visit order; the first mismatch stops it with an error.
struct Reader {
    std::span<const std::byte> in;
    size_t at = k_header_bytes;
    std::string error;

    bool word(void* p)
    {
        if (!error.empty())
            return false;
        if (in.size() - at < 8) {
            error = "damaged snapshot: it ends early";
            return false;
        }
        std::memcpy(p, in.data() + at, 8);
        at += 8;
        return true;
    }
    void real(double& x, Field) { (void)word(&x); }
    template <class T> void integer(T& x, Field)
    {
        uint64_t u = 0;
        if (word(&u))
            x = static_cast<T>(u);
    }
    void flag(bool& b, Field f)
    {
        double x = 0.0;
        real(x, f);
        b = x != 0.0;
    }
    bool check(bool ok, const char* what)
    {
        if (!ok && error.empty())
            error = what;
        return error.empty();
    }
    template <class C> C& sequence(C& c, Field f)
    {
        uint64_t n = 0;
        integer(n, f);
        // Every element takes at least one word: a longer count is damage, not a reason to allocate.
        if (!check(n <= (in.size() - at) / 8, "damaged snapshot: a list is longer than the snapshot"))
            n = 0;
        c.resize(static_cast<size_t>(n));
        return c;
    }
};

// What restore rebuilds from the restored state: the deformed surfaces and the accuracy report's start.
void after_restore(World::Impl& w)
{
    // A pair's proof of being apart is a cache the snapshot does not hold, and a manifold read into a
    // slot that held another pair keeps that pair's proof: drop them all (the next query proves again).
    for (PairManifold& m : w.contact.manifolds)
        m.apart = {};
    for (PairManifold& m : w.contact.parked.manifolds)
        m.apart = {};
    restore_remould(w);
    for (ModalBody& b : w.reg.store<ModalBody>().values()) {
        b.stats.most_active = std::max(b.stats.most_active, b.state.active);
        std::fill(b.stats.last_nodal_load.begin(), b.stats.last_nodal_load.end(), 0.0);
        std::fill(b.stats.last_load.begin(), b.stats.last_load.end(), 0.0);
        b.stats.last_has_load = false;
        update_modal_surface(b);
    }
}

} // namespace

Snapshot Snapshot::from_bytes(std::span<const std::byte> bytes)
{
    Snapshot s;
    s.m_bytes.assign(bytes.begin(), bytes.end());
    return s;
}

uint32_t Snapshot::layout_version() const
{
    if (m_bytes.size() < k_header_bytes || std::memcmp(m_bytes.data(), k_magic, 4) != 0)
        return 0;
    uint32_t version = 0;
    std::memcpy(&version, m_bytes.data() + 4, 4);
    return version;
}

uint64_t World::state_hash() const
{
    Emitter<FnvSink> hasher{};
    visit_state(hasher, std::as_const(*m_impl));
    return hasher.sink.h;
}

Snapshot World::snapshot() const
{
    Snapshot s;
    s.m_bytes.resize(k_header_bytes);
    std::memcpy(s.m_bytes.data(), k_magic, 4);
    std::memcpy(s.m_bytes.data() + 4, &k_snapshot_layout_version, 4);
    Emitter<ByteSink> writer{{s.m_bytes}};
    visit_state(writer, std::as_const(*m_impl));
    return s;
}

Status World::restore(const Snapshot& s)
{
    Impl& w = *m_impl;
    SM_ASSERT(!w.locked, "restore() called while the world steps");
    if (w.locked)
        return Error{"", "snapshot", "cannot restore while the world steps"};
    if (s.layout_version() != k_snapshot_layout_version)
        return Error{"", "snapshot",
                     "snapshot layout version " + std::to_string(s.layout_version()) + ", this build reads " +
                         std::to_string(k_snapshot_layout_version) + " (or not a snapshot)"};
    // Read into the world, then put it back from a copy if the bytes turn out wrong: all or nothing.
    const Snapshot before = snapshot();
    Reader reader{s.m_bytes, k_header_bytes, {}};
    visit_state(reader, w);
    if (reader.error.empty() && reader.at != s.m_bytes.size())
        reader.error = "damaged snapshot: bytes left over after the state";
    if (!reader.error.empty()) {
        Reader undo{before.m_bytes, k_header_bytes, {}};
        visit_state(undo, w);
        SM_ASSERT(undo.error.empty(), "a world's own snapshot always restores");
        return Error{"", "snapshot", reader.error};
    }
    after_restore(w);
    return {};
}

} // namespace supermodal
