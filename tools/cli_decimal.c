#include "cli_decimal.h"

#include <math.h>
#include <stdint.h>

__extension__ typedef unsigned __int128 u128; /* gcc and clang; __extension__: no -Wpedantic warning */

/* 5^0 .. 5^27 (5^27 < 2^63) */
static const uint64_t pow5[28] = {
  1ULL, 5ULL, 25ULL, 125ULL, 625ULL, 3125ULL, 15625ULL, 78125ULL, 390625ULL, 1953125ULL,
  9765625ULL, 48828125ULL, 244140625ULL, 1220703125ULL, 6103515625ULL, 30517578125ULL,
  152587890625ULL, 762939453125ULL, 3814697265625ULL, 19073486328125ULL, 95367431640625ULL,
  476837158203125ULL, 2384185791015625ULL, 11920928955078125ULL, 59604644775390625ULL,
  298023223876953125ULL, 1490116119384765625ULL, 7450580596923828125ULL};

static int bits128(u128 x)
{
  uint64_t hi = (uint64_t)(x >> 64), lo = (uint64_t)x;
  return hi ? 128 - __builtin_clzll(hi) : 64 - __builtin_clzll(lo);
}

/* The double nearest to (N + f) 2^E, 0 <= f < 1, f > 0 iff sticky; N > 0
 * and, when sticky, at least 55 bits long.  Round to nearest, ties to even:
 * the bits below the 53 kept ones are rem (+ f) against half. */
static double round_bin(u128 N, int E, int sticky)
{
  int b = bits128(N);
  if (b <= 53) /* exact (never sticky: see above) */
    return ldexp((double)(uint64_t)N, E);
  int shift = b - 53;
  uint64_t mant = (uint64_t)(N >> shift);
  u128 rem = N & (((u128)1 << shift) - 1), half = (u128)1 << (shift - 1);
  if (rem > half || (rem == half && (sticky || (mant & 1))))
    mant++;
  if (mant == (UINT64_C(1) << 53)) {
    mant >>= 1;
    shift++;
  }
  return ldexp((double)mant, shift + E); /* mant < 2^53: exact; |value| in the normal range */
}

int cli_decimal(const char *s, double *v)
{
  const char *c = s;
  int neg = 0;
  if (*c == '+' || *c == '-')
    neg = *c++ == '-';
  uint64_t m = 0;
  int nd = 0, e10 = 0, any = 0;
  for (; *c >= '0' && *c <= '9'; c++) {
    any = 1;
    if (m == 0 && *c == '0')
      continue; /* leading zeros */
    if (nd == 19)
      return 0;
    m = m * 10 + (uint64_t)(*c - '0');
    nd++;
  }
  if (*c == '.') {
    for (c++; *c >= '0' && *c <= '9'; c++) {
      any = 1;
      e10--;
      if (m == 0 && *c == '0')
        continue;
      if (nd == 19)
        return 0;
      m = m * 10 + (uint64_t)(*c - '0');
      nd++;
    }
  }
  if (!any)
    return 0;
  if (*c == 'e' || *c == 'E') {
    c++;
    int eneg = 0, x = 0, ed = 0;
    if (*c == '+' || *c == '-')
      eneg = *c++ == '-';
    for (; *c >= '0' && *c <= '9'; c++, ed++)
      if (x < 100000)
        x = x * 10 + (*c - '0');
    if (!ed)
      return 0;
    e10 += eneg ? -x : x;
  }
  if (*c != '\0')
    return 0;
  if (m == 0) {
    *v = neg ? -0.0 : 0.0;
    return 1;
  }
  if (e10 < -27 || e10 > 27)
    return 0;
  double r;
  if (e10 >= 0) { /* m 5^e 2^e exactly: m < 2^64, 5^e < 2^63 */
    r = round_bin((u128)m * pow5[e10], e10, 0);
  } else { /* m 2^s / 5^k 2^-(s+k), with m 2^s < 2^127: a quotient of at least 63 bits */
    int k = -e10, sh = 127 - (64 - __builtin_clzll(m));
    u128 num = (u128)m << sh, q = num / pow5[k];
    r = round_bin(q, -sh - k, num - q * pow5[k] != 0);
  }
  *v = neg ? -r : r;
  return 1;
}
