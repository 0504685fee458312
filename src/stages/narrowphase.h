// narrowphase.h — Stage: contact points for every pair, only for the pair kinds in `kinds`.
// Programs: "narrowphase" (sphere–sphere, sphere–hull, sphere–plane, hull–plane) and
// "narrowphase_sat" (hull–hull: SAT over face normals and edge–edge axes, Sutherland–Hodgman
// clipping, reduction to <= 4 points). A program whose kinds are absent is never built.
// Reads pairs, counters[kPairCount], pos, rot, props (shape), shapes and hull tables.
// Writes manifolds[i] for each pair i < min(count, pairCapacity): bodyA/bodyB = the pair's
// rows, normal from B to A, points on B with signed distance (kept below the pair's threshold:
// the smaller of its two shapes' breakingThreshold, m).
#pragma once
#include "world/device_world.h"
#include "world/plan.h"

namespace btgpu {
// The two stages of it: the kinds without SAT (program "narrowphase"), and hull-hull
// ("narrowphase_sat").
void narrowphaseSimple(DeviceWorld& w, const PairKinds& kinds);
void narrowphaseSat(DeviceWorld& w);
// Both, as the kinds ask.
void narrowphase(DeviceWorld& w, const PairKinds& kinds);
}
