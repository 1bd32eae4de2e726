/* mfstab map's choice of the worst sample (tools/cmd_map.c; declared here
 * for tests/test_map_worst.c). */
#ifndef MFSTAB_CMD_MAP_H
#define MFSTAB_CMD_MAP_H

#include <stddef.h>

/* Over the omega^2 w[i nb + b] of n samples of nb branches: the least real
 * part (*min_re) and the largest growth |Im sqrt(omega^2)| (*max_growth,
 * 0 if none), and the first sample in order with a branch whose real part is
 * within 1e-12 scale of *min_re (*imin), whose growth is within 1e-12
 * sqrt(scale) of *max_growth (*igr), scale = max |omega^2|.  Wave vectors
 * equal by symmetry (k and its mirror image) differ only by rounding: this
 * picks the same one whatever the rounding of the machine and the build. */
void map_worst(const double _Complex *w, size_t n, int nb, double scale, double *min_re,
               double *max_growth, size_t *imin, size_t *igr);

#endif
