/*
** fuzz_util.h: helpers shared by the libFuzzer harnesses of tests/fuzz/.
** Harnesses are built by `make fuzz` (see doc/reliability.md, "Fuzzing").
*/
#ifndef TDS_FUZZ_UTIL_H
#define TDS_FUZZ_UTIL_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "tds.h"

/* libFuzzer's entry points, defined by each harness. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

/* Progress lines and warnings are dropped: the harness checks statuses. */
static inline void fuzz_no_output(void *ud, const char *text) {
  (void)ud;
  (void)text;
}

/* A scratch file name private to this process (dumps are written there),
** under $TMPDIR or /tmp. */
static inline const char *fuzz_scratch(const char *suffix) {
  static char path[4][512];
  static int n;
  char *p = path[n++ & 3];
  const char *dir = getenv("TMPDIR");
  snprintf(p, 512, "%s/tds-fuzz-%ld%s", dir && *dir ? dir : "/tmp", (long)getpid(), suffix);
  return p;
}

/* An invariant the harness checks failed: report and abort, so libFuzzer
** records the input as a crash. */
#define FUZZ_CHECK(cond, ...)                                      \
  do {                                                             \
    if (!(cond)) {                                                 \
      fprintf(stderr, "fuzz invariant failed: %s (%s:%d)\n", #cond, \
              __FILE__, __LINE__);                                 \
      fprintf(stderr, __VA_ARGS__);                                \
      fputc('\n', stderr);                                         \
      abort();                                                     \
    }                                                              \
  } while (0)

#endif
