/* counters.h — slots of the device counters buffer, as kernels name them; the host's
 * btgpu::Counter enum (src/world/device_world.h) must agree (checked there). */
#ifndef BTG_COUNTERS_H
#define BTG_COUNTERS_H
#define BTG_COUNTER_PAIRS 0
#define BTG_COUNTER_CONTACTS 1
#define BTG_COUNTER_PREV_CONTACTS 2
#define BTG_COUNTER_STATUS 3
#define BTG_COUNTER_NAN_BODY 4
#define BTG_COUNTER_COLORS_USED 5 /* colors the batching assigned, leftovers excluded */
#define BTG_COUNTER_LEFTOVERS 6   /* contacts left for the serial pass */
#endif
