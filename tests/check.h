/* A minimal test harness: one line per failed check saying what and by how
 * much; a summary line per test program; exit status 1 if anything failed. */
#ifndef MFS_CHECK_H
#define MFS_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_passed = 0, check_failed = 0;

#define CHECK(cond, ...)                                   \
  do {                                                     \
    if (cond) {                                            \
      check_passed++;                                      \
    } else {                                               \
      check_failed++;                                      \
      printf("FAIL %s:%d: ", __FILE__, __LINE__);          \
      printf(__VA_ARGS__);                                 \
      printf("\n");                                        \
    }                                                      \
  } while (0)

/* |got - want| <= tol, printing both and the difference on failure. */
#define CHECK_NEAR(got, want, tol, ...)                                                   \
  do {                                                                                   \
    double g_ = (got), w_ = (want), t_ = (tol);                                          \
    if (fabs(g_ - w_) <= t_ && isfinite(g_)) {                                           \
      check_passed++;                                                                    \
    } else {                                                                             \
      check_failed++;                                                                    \
      printf("FAIL %s:%d: got %.17g want %.17g (diff %.3g > %.3g): ", __FILE__, __LINE__, \
             g_, w_, fabs(g_ - w_), t_);                                                 \
      printf(__VA_ARGS__);                                                               \
      printf("\n");                                                                      \
    }                                                                                    \
  } while (0)

static int check_summary(const char *name)
{
  printf("%s: %d checks passed, %d failed\n", name, check_passed, check_failed);
  return check_failed ? 1 : 0;
}

#endif
