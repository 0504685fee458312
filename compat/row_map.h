// row_map.h — which device row holds which Bullet collision object, kept across adds and
// removes: a removed object's row is retired (excluded on the device) and reused only after a
// step has run without it, new objects take a free row or a new one at the end; nothing else
// moves, so untouched bodies keep their rows, their device state and their warm-start cache.
// Rows are placed in a fixed order (the world's array order, free rows last retired first), so
// the same sequence of adds and removes gives the same rows.
#pragma once
#include <cstddef>
#include <unordered_map>
#include <unordered_set>
#include <vector>

class btCollisionObject;
template <typename T>
class btAlignedObjectArray;

namespace btgpu {

class RowMap {
public:
    struct Changes {
        std::vector<size_t> fresh;    // rows that now hold a new object
        std::vector<size_t> retired;  // rows whose object left
    };
    // Rows = objects in array order; nothing retired or free.
    void reset(const btAlignedObjectArray<btCollisionObject*>& objects);
    // Makes the rows follow the world's objects. `removed`: objects the app removed since the
    // last call; one found in the array again is a new object at a reused address. Reads only
    // the pointers of objects that left (they may be deleted).
    Changes follow(const btAlignedObjectArray<btCollisionObject*>& objects,
                   const std::unordered_set<const btCollisionObject*>& removed);
    // A step ran: rows retired before it may take new objects now (their old contacts have
    // left the warm-start cache).
    void stepped();

    size_t size() const { return m_rows.size(); }
    btCollisionObject* at(size_t r) const { return m_rows[r]; }  // nullptr: retired
    // The row of an object in the world, -1 for one that is not.
    int rowOf(const btCollisionObject* o) const
    {
        auto it = m_rowOf.find(o);
        return it == m_rowOf.end() ? -1 : int(it->second);
    }
    size_t live() const { return m_rows.size() - m_free.size() - m_retiring.size(); }
    size_t unused() const { return m_free.size() + m_retiring.size(); }

private:
    std::vector<btCollisionObject*> m_rows;
    std::unordered_map<const btCollisionObject*, size_t> m_rowOf;
    std::vector<size_t> m_free;      // reusable now
    std::vector<size_t> m_retiring;  // reusable after the next step
};

}  // namespace btgpu
