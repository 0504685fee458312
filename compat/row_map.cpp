// row_map.cpp — reconciling the rows with the world's collision objects.
#include "row_map.h"

#include <LinearMath/btAlignedObjectArray.h>

#include <algorithm>

namespace btgpu {

void RowMap::reset(const btAlignedObjectArray<btCollisionObject*>& objects)
{
    m_rows.assign(size_t(objects.size()), nullptr);
    m_rowOf.clear();
    m_rowOf.reserve(size_t(objects.size()));  // no rehashes on the way (1,000,000 objects)
    m_free.clear();
    m_retiring.clear();
    for (int i = 0; i < objects.size(); ++i) {
        m_rows[size_t(i)] = objects[i];
        m_rowOf[objects[i]] = size_t(i);
    }
}

RowMap::Changes RowMap::follow(const btAlignedObjectArray<btCollisionObject*>& objects,
                               const std::unordered_set<const btCollisionObject*>& removed)
{
    Changes c;
    std::vector<char> seen(m_rows.size(), 0);
    std::vector<btCollisionObject*> added;
    for (int i = 0; i < objects.size(); ++i) {
        btCollisionObject* o = objects[i];
        auto it = m_rowOf.find(o);
        if (it != m_rowOf.end() && !removed.count(o)) seen[it->second] = 1;
        else added.push_back(o);
    }
    for (size_t r = 0; r < m_rows.size(); ++r) {
        if (!m_rows[r] || seen[r]) continue;
        m_rowOf.erase(m_rows[r]);
        m_rows[r] = nullptr;
        m_retiring.push_back(r);
        c.retired.push_back(r);
    }
    for (btCollisionObject* o : added) {
        size_t r;
        if (!m_free.empty()) {
            r = m_free.back();
            m_free.pop_back();
            m_rows[r] = o;
        } else {
            r = m_rows.size();
            m_rows.push_back(o);
        }
        m_rowOf[o] = r;
        c.fresh.push_back(r);
    }
    return c;
}

void RowMap::stepped()
{
    // Lowest rows last in the free list, so they are taken first.
    m_free.insert(m_free.end(), m_retiring.begin(), m_retiring.end());
    m_retiring.clear();
    std::sort(m_free.begin(), m_free.end(), [](size_t a, size_t b) { return a > b; });
}

}  // namespace btgpu
