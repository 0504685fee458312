// manifold_table.h — the dispatcher manifolds ManifoldSync holds, by key: nodes that keep their
// address while they are in the table (the fill's lists name them by pointer), found through a
// flat open-addressing index (linear probing, power-of-two size, each slot's hash beside its
// node). Why not std::unordered_map: the fill looks up every report's manifold each step (about
// 30,000 at 8,000 resting cubes), and the map's lookup — a division for the bucket, then a
// chain of separately allocated nodes — was most of that pass (perf on PoCL's host); here a
// lookup is a multiply-shift hash, one slot line and the node itself. Iteration follows the
// nodes' storage, not their addresses: the same adds and removes give the same order.
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

namespace btgpu {

template <typename Key, typename Entry, typename Hash>
class ManifoldTable {
public:
    struct Node {
        Key first;
        Entry second;
        bool inUse = false;
    };

    // The node of key, nullptr when none. Safe from several threads while nothing inserts or erases.
    Node* find(const Key& key) const { return find(key, Hash()(key)); }
    Node* find(const Key& key, size_t h) const
    {
        if (m_count == 0) return nullptr;
        for (size_t i = h & m_mask;; i = (i + 1) & m_mask) {
            const Slot& s = m_slots[i];
            if (!s.node) return nullptr;
            if (s.hash == h && s.node->first == key) return s.node;
        }
    }
    // For many lookups in a row (a pass over reports): what find(key, h) will read, fetched ahead
    // in two steps a few keys apart, so that the misses of many lookups overlap: the key's home
    // slot, then (once that has arrived) the node it names.
    void prefetchSlot(size_t h) const
    {
        if (m_count) __builtin_prefetch(&m_slots[h & m_mask]);
    }
    void prefetchNode(size_t h) const
    {
        if (!m_count) return;
        if (const Node* n = m_slots[h & m_mask].node) __builtin_prefetch(n);
    }
    // The node of key, made (its entry value-initialised) when there was none.
    Node* insert(const Key& key)
    {
        if (Node* n = find(key)) return n;
        if ((m_count + 1) * 2 > m_slots.size()) grow();
        Node* n;
        if (!m_free.empty()) {
            n = m_free.back();
            m_free.pop_back();
        } else {
            m_nodes.emplace_back();
            n = &m_nodes.back();
        }
        n->first = key;
        n->second = Entry{};
        n->inUse = true;
        place(Hash()(key), n);
        ++m_count;
        return n;
    }
    // As a set: whether key was new; key gone (if there).
    bool add(const Key& key)
    {
        const size_t before = m_count;
        insert(key);
        return m_count != before;
    }
    void eraseKey(const Key& key) { erase(find(key)); }
    void erase(Node* n)
    {
        if (!n || !n->inUse) return;
        const size_t h = Hash()(n->first);
        size_t i = h & m_mask;
        while (m_slots[i].node != n) i = (i + 1) & m_mask;
        // Backward-shift deletion: each later slot of the run moves into the hole unless its
        // home lies cyclically in (hole, slot], so no lookup ever meets a gap before its key.
        for (size_t j = i;;) {
            j = (j + 1) & m_mask;
            if (!m_slots[j].node) break;
            const size_t home = m_slots[j].hash & m_mask;
            const bool stays = j > i ? (home > i && home <= j) : (home > i || home <= j);
            if (!stays) {
                m_slots[i] = m_slots[j];
                i = j;
            }
        }
        m_slots[i] = Slot{};
        n->inUse = false;
        n->second = Entry{};
        m_free.push_back(n);
        --m_count;
    }
    void clear()
    {
        m_nodes.clear();
        m_free.clear();
        m_slots.clear();
        m_mask = 0;
        m_count = 0;
    }
    size_t size() const { return m_count; }
    // f(node) for each node in the table, in storage order.
    template <typename F>
    void forEach(F f)
    {
        for (Node& n : m_nodes)
            if (n.inUse) f(&n);
    }

private:
    struct Slot {
        size_t hash = 0;
        Node* node = nullptr;
    };
    void place(size_t h, Node* n)
    {
        size_t i = h & m_mask;
        while (m_slots[i].node) i = (i + 1) & m_mask;
        m_slots[i] = Slot{h, n};
    }
    void grow()
    {
        std::vector<Slot> old;
        old.swap(m_slots);
        m_slots.assign(old.empty() ? 64 : old.size() * 2, Slot{});
        m_mask = m_slots.size() - 1;
        for (const Slot& s : old)
            if (s.node) place(s.hash, s.node);
    }

    std::deque<Node> m_nodes;  // storage: a deque keeps every node where it is
    std::vector<Node*> m_free;
    std::vector<Slot> m_slots;
    size_t m_mask = 0;
    size_t m_count = 0;
};

}  // namespace btgpu
