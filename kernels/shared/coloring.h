/* coloring.h — the batching's contact priority, shared by the kernel and its CPU reference. */
#ifndef BTG_COLORING_H
#define BTG_COLORING_H
#include "prelude.h"

#define BTG_COLOR_SUB_ROUNDS 3 /* claim/assign passes that fill one color */

/* A bijection of the contact index onto uints (odd multiplies and xor-shifts are invertible,
 * and so is a rotation), so priorities are unique and look random: neighbouring contacts do not
 * form the long chains of losers that plain index order gives. Unique matters: two edges of
 * equal priority that share a body both win it and take the same colour, and their solves then
 * race on that body. Until 2026-12-06 the hash's top bit was dropped (an int priority), which is
 * not a bijection: edges 88,337 and 112,962 had the same priority (4 such pairs below 300,000
 * edges, 99 below a million; ColorPriority.UniqueOverFourMillionEdges). The hash rotated left by
 * one bit orders every other pair as the old priority did (its low 31 bits first, then the
 * dropped bit), so every coloring without such a tie is the one it was. */
static inline uint btgColorPriority(int i)
{
    uint x = (uint)i * 0x9E3779B1u;
    x ^= x >> 15;
    x *= 0x85EBCA77u;
    x ^= x >> 13;
    return (x << 1) | (x >> 31);
}

#endif
