/* counters.h — slots of the device counters buffer and the mode values launchers pass to
 * kernels, defined once: kernels and CPU references use these names, the host's
 * btgpu::Counter enum (src/world/device_world.h) takes its values from them. */
#ifndef BTG_COUNTERS_H
#define BTG_COUNTERS_H
#define BTG_COUNTER_PAIRS 0
#define BTG_COUNTER_CONTACTS 1
#define BTG_COUNTER_PREV_CONTACTS 2
#define BTG_COUNTER_STATUS 3
#define BTG_COUNTER_NAN_BODY 4
#define BTG_COUNTER_COLORS_USED 5 /* colors the batching assigned, leftovers excluded */
#define BTG_COUNTER_LEFTOVERS 6   /* constraint-graph edges left for the serial pass */
#define BTG_COUNTER_EDGES 7       /* constraint-graph edges: the contacts, then other kinds' */
#define BTG_COUNTER_SUB_PAIRS 8   /* midphase (convex, triangle) sub-pairs found, even past capacity */
#define BTG_COUNTER_SOFT_MASS_RATIO 9 /* the soft step's prepare: the float bits of the largest mass ratio
                                        (heavier over lighter) of an edge between two dynamic bodies */
#define BTG_COUNTER_SOFT_BOUNCE 10 /* soft_resident: nonzero when a soft contact of the step may bounce */
#define BTG_NUM_COUNTERS 11

/* Solver passes (solve_constraints, solve_jacobi): warm start, a velocity iteration, a
 * split-impulse push iteration. The batched PGS sweeps a velocity iteration's contacts twice,
 * as Bullet's solveSingleIteration does: every contact's normal rows, then every friction row
 * (each bounded by its point's normal impulse of this iteration). Solving each contact's
 * friction right after its own normals pushed the round tower of BenchmarkDemo's test 2
 * outward (regression Stacking.BenchTowerStaysLikeStock). */
#define BTG_PASS_WARM_START 0
#define BTG_PASS_VELOCITY 1
#define BTG_PASS_PUSH 2
#define BTG_PASS_NORMALS 3
#define BTG_PASS_FRICTION 4
#define BTG_PASS_ROLLING 5 /* then, with rolling friction, every rolling row (BtgRollingContact) */

/* Pair sort keys (find_pairs' pair_sort_keys): (a, b) packed in one key, or two stable
 * passes: b (minor) first, then a. */
#define BTG_PAIR_KEY_PACKED 0
#define BTG_PAIR_KEY_MINOR 1
#define BTG_PAIR_KEY_MAJOR 2
#endif
