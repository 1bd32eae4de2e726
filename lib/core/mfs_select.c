#include "mfs_select.h"

#include <stdint.h>
#include <string.h>

/* The order of doubles (NaN aside) as the order of unsigned 64-bit keys:
 * a positive value's bits with the sign bit set, a negative value's bits
 * complemented. */
static uint64_t order_key(double v)
{
  uint64_t u;
  memcpy(&u, &v, sizeof u);
  return u >> 63 ? ~u : u | (UINT64_C(1) << 63);
}

static double key_value(uint64_t k)
{
  uint64_t u = k >> 63 ? k & ~(UINT64_C(1) << 63) : ~k;
  double v;
  memcpy(&v, &u, sizeof v);
  return v;
}

/* Radix selection on the keys, eight bits a pass from the top: a 256-bin
 * histogram on the stack, no copy.  k is kept as the rank among the values
 * whose keys share the digits chosen. */
double mfs_kth_smallest(const double *v, size_t n, size_t stride, size_t k)
{
  uint64_t prefix = 0, mask = 0;
  for (int shift = 56; shift >= 0; shift -= 8) {
    size_t cnt[256] = {0};
    for (size_t i = 0; i < n; i++) {
      uint64_t key = order_key(v[i * stride]);
      if ((key & mask) == prefix)
        cnt[(key >> shift) & 255u]++;
    }
    unsigned d = 0;
    while (k >= cnt[d]) /* more than k values match the prefix: d stays below 256 */
      k -= cnt[d++];
    prefix |= (uint64_t)d << shift;
    mask |= (uint64_t)255u << shift;
  }
  return key_value(prefix);
}

void mfs_quartiles(int dim, size_t n, const double *x, double *q1, double *q3)
{
  size_t step = n > 4096 ? n / 4096 : 1, m = (n - 1) / step + 1;
  for (int k = 0; k < dim; k++) {
    q1[k] = mfs_kth_smallest(x + k, m, (size_t)dim * step, (m - 1) / 4);
    q3[k] = mfs_kth_smallest(x + k, m, (size_t)dim * step, 3 * (m - 1) / 4);
  }
}
