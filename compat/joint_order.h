// joint_order.h — stock's solve order of the world's joints, as colours for the bullet mode.
// Stock solves a step's joints in the order btDiscreteDynamicsWorld::solveConstraints leaves
// them: a copy of m_constraints sorted by island id with btAlignedObjectArray::quickSort, which
// is not stable, so even the joints of one island come out permuted (three of them reversed).
// Two joints that share a body give different answers in different orders (a servo arm's tip
// 3 cm apart), so the bullet mode colours them in that order: each joint one colour above every
// joint before it that shares a dynamic body with it.
#pragma once
#include <vector>

class btDiscreteDynamicsWorld;

namespace btgpu {

// Joint i's place in stock's solve order of this step: order[k] is the world's constraint index
// solved k-th. The island ids are the union-find roots of stock's
// calculateSimulationIslands over the joints alone (stock unites the broadphase's overlapping
// pairs first, which the GPU path does not keep; they only matter where the joints make several
// islands, whose roots they can change).
std::vector<int> stockJointOrder(const btDiscreteDynamicsWorld& world);

// Each joint's colour level in that order (0 where no joint before it shares a dynamic body);
// empty when no two joints share one (then the order makes no difference).
std::vector<int> stockJointLevels(const btDiscreteDynamicsWorld& world);

}  // namespace btgpu
