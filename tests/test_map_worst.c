/* mfstab map's choice of the worst sample (tools/cmd_map.c map_worst): a
 * wave vector and its mirror image have the same omega^2 but for rounding,
 * and the map must name the same one whichever of the two the rounding makes
 * lower (the first in order), while a value lower by more than 1e-12 of the
 * scale still wins; the extremes themselves are the exact least and largest
 * values. */
#include <complex.h>
#undef I
#include <math.h>

#include "check.h"
#include "cmd_map.h"

static void pick(const double complex *w, size_t n, int nb, size_t want_min, size_t want_gr,
                 const char *what)
{
  double scale = 0.0, lo, hi;
  for (size_t i = 0; i < n * (size_t)nb; i++)
    scale = fmax(scale, cabs(w[i]));
  size_t imin = 99, igr = 99;
  map_worst(w, n, nb, scale, &lo, &hi, &imin, &igr);
  double elo = INFINITY, ehi = 0.0;
  for (size_t i = 0; i < n * (size_t)nb; i++) {
    elo = fmin(elo, creal(w[i]));
    ehi = fmax(ehi, fabs(cimag(csqrt(w[i]))));
  }
  CHECK(imin == want_min, "%s: least omega^2 at sample %zu, want %zu", what, imin, want_min);
  CHECK(igr == want_gr, "%s: largest growth at sample %zu, want %zu", what, igr, want_gr);
  CHECK(lo == elo && hi == ehi, "%s: extremes %.17g %.17g, want %.17g %.17g", what, lo, hi, elo,
        ehi);
}

int main(void)
{
  const double up = nextafter(1.0, 2.0), down = nextafter(1.0, 0.0);
  /* a mirror pair (samples 1 and 2) an ulp apart, either way round: sample 1 */
  pick((double complex[]){2.0, up, 1.0, 3.0}, 4, 1, 1, 0, "pair, the second lower");
  pick((double complex[]){2.0, 1.0, up, 3.0}, 4, 1, 1, 0, "pair, the first lower");
  pick((double complex[]){2.0, 1.0, down, 3.0}, 4, 1, 1, 0, "pair, the second lower by an ulp");
  /* lower by 1e-9 of the scale: that one, wherever it is */
  pick((double complex[]){2.0, 1.0, 1.0 - 3e-9, 3.0}, 4, 1, 2, 0, "a real minimum");
  /* unstable (negative omega^2): the growth sqrt(4) at samples 1 and 3, equal
   * but for rounding: the first; the least omega^2 the same way */
  pick((double complex[]){1.0, -4.0 * up, 0.5, -4.0}, 4, 1, 1, 1, "growth pair");
  pick((double complex[]){1.0, -4.0, 0.5, -4.0 * up}, 4, 1, 1, 1, "growth pair, reversed");
  /* two branches per sample: the tie is in the second branch of samples 0
   * and 2 */
  pick((double complex[]){5.0, 0.25 * up, 5.0, 4.0, 6.0, 0.25}, 3, 2, 0, 0, "branches");
  /* complex omega^2 (a flutter-type growth): |Im sqrt| 1 at samples 0 and 1 */
  pick((double complex[]){CMPLX(0.0, 2.0 * up), CMPLX(0.0, 2.0), 1.0}, 3, 1, 0, 0,
       "complex pair");
  return check_summary("test_map_worst");
}
