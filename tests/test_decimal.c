/* tools/cli_decimal.c against the C library's strtod: bit-identical doubles
 * on many random decimals (the particle files' %.17g, shorter and longer
 * mantissas, exponents from -27 to 27 and beyond, ties and their
 * neighbours), and every string it declines is one cli_parse_double still
 * reads through strtod. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "cli.h"
#include "cli_decimal.h"

static uint64_t rng = 0x9E3779B97F4A7C15ULL;
static uint64_t next(void)
{
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return rng;
}

static long handled = 0, declined = 0;

static void one(const char *s)
{
  double a = 0.0, b = strtod(s, NULL), p = 0.0;
  if (!cli_decimal(s, &a)) {
    declined++;
    return;
  }
  handled++;
  uint64_t ua, ub;
  memcpy(&ua, &a, 8);
  memcpy(&ub, &b, 8);
  CHECK(ua == ub, "cli_decimal(\"%s\") = %.17g (bits %016llx), strtod %.17g (bits %016llx)", s,
        a, (unsigned long long)ua, b, (unsigned long long)ub);
  /* and through cli_parse_double, which uses it */
  CHECK(cli_parse_double(s, &p) && memcmp(&p, &b, 8) == 0, "cli_parse_double(\"%s\") = %.17g", s,
        p);
}

int main(void)
{
  char s[128];
  int fails0;
  /* random doubles as the particle files print them, and shorter */
  static const char *fmt[] = {"%.17g", "%.16g", "%.15g", "%.6g", "%.3e", "%.19e", "%.1f", "%.12f"};
  for (int r = 0; r < 400000; r++) {
    uint64_t u = next();
    double x;
    int kind = r % 4;
    if (kind == 0) { /* uniform in [0, 1) */
      x = (double)(u >> 11) * 0x1.0p-53;
    } else if (kind == 1) { /* any sign, magnitudes 1e-25 .. 1e25 */
      x = ((double)(u >> 11) * 0x1.0p-53 - 0.5) * pow(10.0, (double)(int)(next() % 51) - 25);
    } else if (kind == 2) { /* raw bit patterns in the normal range around 1 */
      uint64_t bits = (u & 0x000FFFFFFFFFFFFFULL) | ((uint64_t)(1023 - 60 + next() % 120) << 52);
      memcpy(&x, &bits, 8);
    } else { /* a lattice of the unit square and its volumes */
      x = (double)(u % 1000) / 999.0 + 1e-3 * ((double)(next() >> 11) * 0x1.0p-53 - 0.5);
    }
    snprintf(s, sizeof s, fmt[r % 8], x);
    one(s);
  }
  /* random digit strings: 1 to 19 digits, a point anywhere, exponents -40 .. 40 */
  for (int r = 0; r < 300000; r++) {
    int nd = 1 + (int)(next() % 19), pt = (int)(next() % (uint64_t)(nd + 1)), k = 0;
    if (next() % 2)
      s[k++] = next() % 2 ? '-' : '+';
    for (int i = 0; i < nd; i++) {
      if (i == pt && i > 0)
        s[k++] = '.';
      s[k++] = (char)('0' + next() % 10);
    }
    if (next() % 2)
      k += snprintf(s + k, sizeof s - (size_t)k, "%c%d", next() % 2 ? 'e' : 'E',
                    (int)(next() % 81) - 40);
    s[k] = '\0';
    one(s);
  }
  /* exact halfway cases between neighbouring doubles, and one unit of the
   * last of 19 digits either side (the ties to even, and the sticky bit) */
  for (int r = 0; r < 100000; r++) {
    double x = (double)(next() >> 11) * 0x1.0p-53 * pow(2.0, (double)(int)(next() % 40) - 20);
    double y = nextafter(x, 2.0 * x + 1.0);
    long double mid = ((long double)x + (long double)y) / 2.0L; /* 64-bit mantissa: exact */
    snprintf(s, sizeof s, "%.40Lg", mid);
    one(s); /* mostly declined (many digits); strtod then */
    snprintf(s, sizeof s, "%.18Le", mid);
    one(s);
    snprintf(s, sizeof s, "%.17Le", mid);
    one(s);
  }
  fails0 = check_failed;
  static const char *fixed[] = {"0", "-0", "+0", "0.0", "-0.000", "1", "-1", "0.5", "1e0", "1E+2",
                                "1.7976931348623157e308", "4.9e-324", "2.2250738585072014e-308",
                                "9007199254740993", "9007199254740992.5", "9999999999999999999",
                                "0.1", "0.2", "0.3", "1e27", "1e-27", "123456789012345678.9e-5",
                                "00000000000000000000000001.5", "0.0000000000000000000000000001",
                                "5e-28", "1.", ".5", "-.5e1", "7.450580596923828125e-9"};
  for (size_t i = 0; i < sizeof fixed / sizeof *fixed; i++)
    one(fixed[i]);
  /* what it declines still parses (by strtod in cli_parse_double) */
  double v;
  CHECK(!cli_decimal("12345678901234567890", &v) && cli_parse_double("12345678901234567890", &v) &&
          v == strtod("12345678901234567890", NULL),
        "20 digits: declined, then strtod");
  CHECK(!cli_decimal("1e28", &v) && !cli_decimal("1e-28", &v) && !cli_decimal("1e", &v) &&
          !cli_decimal("e5", &v) && !cli_decimal(".", &v) && !cli_decimal("1.5x", &v) &&
          !cli_decimal("nan", &v) && !cli_decimal("0x10", &v) && !cli_decimal("", &v),
        "declines what it does not read exactly");
  CHECK(handled > 700000, "handled %ld of %ld strings (declined %ld)", handled, handled + declined,
        declined);
  printf("test_decimal: %ld strings converted, %ld declined, %d mismatches in the random sets\n",
         handled, declined, fails0);
  return check_summary("test_decimal");
}
