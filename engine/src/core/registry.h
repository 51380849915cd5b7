// SPDX-License-Identifier: MIT
// Entity registry: a generational entity pool plus one sparse set per component type, from a fixed,
// compile-time list (no type-keyed map, no RTTI). EnTT's idea, written small.
//
// Iteration order of a component store is its history (swap-and-pop on removal), the same for the same
// sequence of calls; systems write only to the entity they visit, so order never changes results.
// Hashes and summaries walk entities in index order instead (EntityPool::for_each_alive).
#pragma once

#include "supermodal/entity.h"

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace supermodal
{

/// Hands out slots with generations. Slot 0 is reserved so Entity{} is null. A slot whose generation
/// would wrap is retired rather than reused, so a stale handle can never alias a live one.
class EntityPool
{
  public:
    static constexpr uint32_t k_max_generation = std::numeric_limits<uint32_t>::max();

    [[nodiscard]] Entity create()
    {
        if (!m_free.empty()) {
            const uint32_t index = m_free.back();
            m_free.pop_back();
            m_alive[index] = true;
            ++m_alive_count;
            return {index, m_generation[index]};
        }
        if (m_generation.empty()) { // reserve slot 0 for the null handle
            m_generation.push_back(0);
            m_alive.push_back(false);
        }
        m_generation.push_back(1);
        m_alive.push_back(true);
        ++m_alive_count;
        return {static_cast<uint32_t>(m_generation.size() - 1), 1};
    }

    /// Returns false (and changes nothing) for a null or stale handle.
    bool destroy(Entity e)
    {
        if (!valid(e))
            return false;
        m_alive[e.index] = false;
        --m_alive_count;
        if (m_generation[e.index] < k_max_generation - 1) {
            ++m_generation[e.index];
            m_free.push_back(e.index);
        } else {
            m_generation[e.index] = k_max_generation; // retired for good
        }
        return true;
    }

    [[nodiscard]] bool valid(Entity e) const
    {
        return e.index != 0 && e.index < m_generation.size() && m_alive[e.index] &&
               m_generation[e.index] == e.generation;
    }

    [[nodiscard]] std::size_t alive_count() const { return m_alive_count; }
    /// Number of slots ever made (including slot 0); an upper bound for index-ordered arrays.
    [[nodiscard]] std::size_t slot_count() const { return m_generation.size(); }

    /// The live entity in slot `index`.
    [[nodiscard]] Entity at(uint32_t index) const { return {index, m_generation[index]}; }

    /// Calls fn(Entity) for each live entity in increasing index order.
    template <class Fn> void for_each_alive(Fn&& fn) const
    {
        for (uint32_t i = 1; i < m_generation.size(); ++i)
            if (m_alive[i])
                fn(Entity{i, m_generation[i]});
    }

    /// Test hook: sets a slot's generation so wrap-around can be tested without 4e9 cycles.
    void debug_set_generation(uint32_t index, uint32_t generation) { m_generation[index] = generation; }

  private:
    std::vector<uint32_t> m_generation;
    std::vector<bool> m_alive;
    std::vector<uint32_t> m_free;
    std::size_t m_alive_count = 0;
};

/// Dense storage of one component type: sparse index → dense position, packed entities and values.
template <class T> class SparseSet
{
  public:
    static constexpr uint32_t k_absent = std::numeric_limits<uint32_t>::max();

    [[nodiscard]] bool contains(Entity e) const
    {
        return e.index < m_sparse.size() && m_sparse[e.index] != k_absent &&
               m_dense[m_sparse[e.index]].generation == e.generation;
    }

    /// Adds (or replaces) the component of e.
    T& emplace(Entity e, T value)
    {
        if (contains(e))
            return m_data[m_sparse[e.index]] = std::move(value);
        if (e.index >= m_sparse.size())
            m_sparse.resize(e.index + 1, k_absent);
        m_sparse[e.index] = static_cast<uint32_t>(m_dense.size());
        m_dense.push_back(e);
        m_data.push_back(std::move(value));
        return m_data.back();
    }

    /// Swap-and-pop removal; returns false if e has no such component.
    bool remove(Entity e)
    {
        if (!contains(e))
            return false;
        const uint32_t pos = m_sparse[e.index];
        const uint32_t last = static_cast<uint32_t>(m_dense.size() - 1);
        if (pos != last) {
            m_dense[pos] = m_dense[last];
            m_data[pos] = std::move(m_data[last]);
            m_sparse[m_dense[pos].index] = pos;
        }
        m_dense.pop_back();
        m_data.pop_back();
        m_sparse[e.index] = k_absent;
        return true;
    }

    [[nodiscard]] T& get(Entity e)
    {
        assert(contains(e) && "component missing or stale handle");
        return m_data[m_sparse[e.index]];
    }
    [[nodiscard]] const T& get(Entity e) const
    {
        assert(contains(e) && "component missing or stale handle");
        return m_data[m_sparse[e.index]];
    }
    [[nodiscard]] T* find(Entity e) { return contains(e) ? &m_data[m_sparse[e.index]] : nullptr; }
    [[nodiscard]] const T* find(Entity e) const { return contains(e) ? &m_data[m_sparse[e.index]] : nullptr; }

    [[nodiscard]] std::size_t size() const { return m_dense.size(); }
    [[nodiscard]] const std::vector<Entity>& entities() const { return m_dense; }
    [[nodiscard]] std::vector<T>& values() { return m_data; }
    [[nodiscard]] const std::vector<T>& values() const { return m_data; }

    void reserve(std::size_t n)
    {
        m_dense.reserve(n);
        m_data.reserve(n);
    }

  private:
    std::vector<uint32_t> m_sparse;
    std::vector<Entity> m_dense;
    std::vector<T> m_data;
};

/// An entity pool and one store per listed component type.
template <class... Components> class BasicRegistry
{
  public:
    [[nodiscard]] Entity create() { return m_pool.create(); }

    /// Removes every component of e, then retires the handle. False for a stale handle.
    bool destroy(Entity e)
    {
        if (!m_pool.valid(e))
            return false;
        (store<Components>().remove(e), ...);
        return m_pool.destroy(e);
    }

    [[nodiscard]] bool valid(Entity e) const { return m_pool.valid(e); }
    [[nodiscard]] const EntityPool& pool() const { return m_pool; }
    [[nodiscard]] EntityPool& pool() { return m_pool; }

    template <class T> T& emplace(Entity e, T value)
    {
        assert(valid(e) && "emplace on a stale handle");
        return store<T>().emplace(e, std::move(value));
    }
    template <class T> bool remove(Entity e) { return store<T>().remove(e); }
    template <class T> [[nodiscard]] bool has(Entity e) const { return store<T>().contains(e); }
    template <class T> [[nodiscard]] T& get(Entity e) { return store<T>().get(e); }
    template <class T> [[nodiscard]] const T& get(Entity e) const { return store<T>().get(e); }
    template <class T> [[nodiscard]] T* find(Entity e) { return store<T>().find(e); }
    template <class T> [[nodiscard]] const T* find(Entity e) const { return store<T>().find(e); }

    template <class T> [[nodiscard]] SparseSet<T>& store() { return std::get<SparseSet<T>>(m_stores); }
    template <class T> [[nodiscard]] const SparseSet<T>& store() const
    {
        return std::get<SparseSet<T>>(m_stores);
    }

    /// Calls fn(Entity, First&, Rest&...) for every entity holding all listed components. Drives from
    /// the smallest store and probes the others (EnTT's view). fn must not add or remove components.
    template <class First, class... Rest, class Fn> void each(Fn&& fn)
    {
        const std::vector<Entity>* driver = &store<First>().entities();
        ((driver = store<Rest>().size() < driver->size() ? &store<Rest>().entities() : driver), ...);
        for (std::size_t i = 0; i < driver->size(); ++i) {
            const Entity e = (*driver)[i];
            if (store<First>().contains(e) && (store<Rest>().contains(e) && ...))
                fn(e, store<First>().get(e), store<Rest>().get(e)...);
        }
    }

    /// Calls fn(Entity, First&, Rest&...) for the entities at positions [begin, end) of First's store that
    /// hold all listed components: a slice for one thread part (parts of one store never overlap).
    template <class First, class... Rest, class Fn> void each_in(std::size_t begin, std::size_t end, Fn&& fn)
    {
        const std::vector<Entity>& dense = store<First>().entities();
        std::vector<First>& values = store<First>().values();
        for (std::size_t i = begin; i < end && i < dense.size(); ++i) {
            const Entity e = dense[i];
            if ((store<Rest>().contains(e) && ...))
                fn(e, values[i], store<Rest>().get(e)...);
        }
    }

  private:
    EntityPool m_pool;
    std::tuple<SparseSet<Components>...> m_stores;
};

} // namespace supermodal
