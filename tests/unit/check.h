/*
** check.h: a tiny test harness for the C unit tests.
**
** Each test is a function run through RUN(fn); checks inside it record
** failures. RUN prints "PASS name" or "FAIL name" (with the first failing
** check), which tests/run.sh counts. main() ends with `return check_done();`.
*/
#ifndef TDS_CHECK_H
#define TDS_CHECK_H

#include <math.h>
#include <stdio.h>
#include <string.h>

static int check_failed_;      /* failures in the current test */
static int check_nfail_, check_npass_;
static char check_msg_[512];

#define CHECK(cond)                                                        \
  do {                                                                     \
    if (!(cond)) {                                                         \
      if (!check_failed_++)                                                \
        snprintf(check_msg_, sizeof check_msg_, "%s:%d: %s", __FILE__,     \
                 __LINE__, #cond);                                         \
    }                                                                      \
  } while (0)

/* |a - b| <= tol * max(1, |b|) (relative above 1, absolute below). */
#define CHECK_NEAR(a, b, tol)                                              \
  do {                                                                     \
    double a_ = (a), b_ = (b), t_ = (tol) * (fabs(b_) > 1 ? fabs(b_) : 1); \
    if (!(fabs(a_ - b_) <= t_)) {                                          \
      if (!check_failed_++)                                                \
        snprintf(check_msg_, sizeof check_msg_,                            \
                 "%s:%d: %s = %.17g, expected %.17g (tol %g)", __FILE__,   \
                 __LINE__, #a, a_, b_, (double)(tol));                     \
    }                                                                      \
  } while (0)

#define RUN(fn)                                                            \
  do {                                                                     \
    check_failed_ = 0;                                                     \
    fn();                                                                  \
    if (check_failed_) {                                                   \
      check_nfail_++;                                                      \
      printf("FAIL %s: %s\n", #fn, check_msg_);                            \
    } else {                                                               \
      check_npass_++;                                                      \
      printf("PASS %s\n", #fn);                                            \
    }                                                                      \
    fflush(stdout);                                                        \
  } while (0)

static inline int check_done(void) { return check_nfail_ ? 1 : 0; }

#endif
