/* coloring.h — the batching's contact priority, shared by the kernel and its CPU reference. */
#ifndef BTG_COLORING_H
#define BTG_COLORING_H
#include "prelude.h"

#define BTG_COLOR_SUB_ROUNDS 3 /* claim/assign passes that fill one color */

/* A bijection of the contact index onto non-negative ints (odd multiplies and xor-shifts are
 * invertible), so priorities are unique and look random: neighbouring contacts do not form the
 * long chains of losers that plain index order gives. */
static inline int btgColorPriority(int i)
{
    uint x = (uint)i * 0x9E3779B1u;
    x ^= x >> 15;
    x *= 0x85EBCA77u;
    x ^= x >> 13;
    return (int)(x & 0x7fffffffu);
}

#endif
