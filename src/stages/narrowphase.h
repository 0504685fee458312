// narrowphase.h — Stage: contact points for every pair, one kernel per row of the pair-kind
// table (kernels/shared/pair_kinds.h) whose kind the plan has. Programs: "narrowphase"
// (sphere–hull, sphere–plane, sphere–box: closed forms, one fresh point a step; two spheres are
// "narrowphase_gjk"'s, stock's point while they touch) and "narrowphase_sat" (two boxes). A program
// whose kinds are absent is never built.
// Reads pairs, pairOrder and pairKindRanges (find_pairs' grouping by kind: each kernel strides
// over its kind's range), pos, rot, props (shape), shapes and hull tables.
// Writes manifolds[i] for each pair i < min(count, pairCapacity): bodyA/bodyB = the pair's
// rows, sub-shape keys (BTG_NO_SUB_SHAPE for today's whole convex shapes), points on B with
// signed distance, normal from B to A and feature id (kept below the pair's threshold: the
// smaller of its two shapes' breakingThreshold, m); and pairManifolds[i], the pair's range of
// manifolds with points (today (i, 1) or (i, 0)).
#pragma once
#include "world/device_world.h"
#include "world/plan.h"

namespace btgpu {
// One narrowphase stage: the kernels of `program` for the kinds in `kinds`.
void narrowphaseProgram(DeviceWorld& w, const PairKinds& kinds, const char* program);
// The convex–triangle kernels of "narrowphase_mesh" over the midphase's sub-pairs, then each
// mesh pair's manifolds gathered from its triangles' (pairManifolds: past the pair slots).
void narrowphaseMesh(DeviceWorld& w, const PairKinds& kinds);
// Every program, as the kinds ask (the mesh one needs the midphase run first).
void narrowphase(DeviceWorld& w, const PairKinds& kinds);
}
