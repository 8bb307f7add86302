/*
** replay.c: run a fuzz harness over its seed corpus without libFuzzer, as
** a test of `make test` (and of `make test-asan`, under the sanitizers).
** Linked with one harness (tests/fuzz/fuzz_NAME.c) into build/test_fuzz_NAME;
** replays every file of tests/fuzz/corpus/NAME (run from the project
** root, as tests/run.sh does), each in a child process so one crashing
** input is reported by name and the others still run. Prints
** "PASS fuzz/NAME: N inputs" or one "FAIL fuzz/NAME/FILE: ..." per bad
** input.
*/
#include <dirent.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv) __attribute__((weak));

#ifndef FUZZ_NAME
#error "build with -DFUZZ_NAME=\"fe\" (the harness's name)"
#endif

static int cmp(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

static int run_one(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return -1;
  size_t cap = 4096, n = 0;
  uint8_t *buf = malloc(cap);
  size_t got;
  while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
    n += got;
    if (n == cap) {
      uint8_t *b = realloc(buf, cap *= 2);
      if (!b) free(buf);
      buf = b;
    }
  }
  fclose(f);
  if (!buf) return -1;
  /* An exact-size copy, so the sanitizers see reads past the input. */
  uint8_t *exact = malloc(n ? n : 1);
  if (!exact) return -1;
  memcpy(exact, buf, n);
  free(buf);
  LLVMFuzzerTestOneInput(exact, n);
  free(exact);
  return 0;
}

int main(int argc, char **argv) {
  const char *dir = argc > 1 ? argv[1] : "tests/fuzz/corpus/" FUZZ_NAME;
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  DIR *d = opendir(dir);
  if (!d) {
    printf("FAIL fuzz/%s: cannot open %s: %s\n", FUZZ_NAME, dir, strerror(errno));
    return 0;
  }
  char **names = NULL;
  size_t n = 0;
  struct dirent *e;
  while ((e = readdir(d))) {
    if (e->d_name[0] == '.') continue;
    char **nn = realloc(names, (n + 1) * sizeof *names);
    if (!nn || !(nn[n] = strdup(e->d_name))) return 1;
    names = nn;
    n++;
  }
  closedir(d);
  qsort(names, n, sizeof *names, cmp);
  int bad = 0;
  for (size_t i = 0; i < n; i++) {
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, names[i]);
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
      int rc = run_one(path);
      fflush(NULL);
      _exit(rc ? 3 : 0);
    }
    int status = 0;
    if (pid < 0 || waitpid(pid, &status, 0) < 0) {
      printf("FAIL fuzz/%s/%s: cannot run: %s\n", FUZZ_NAME, names[i], strerror(errno));
      bad++;
    } else if (WIFSIGNALED(status)) {
      printf("FAIL fuzz/%s/%s: signal %d (run build-fuzz/fuzz_%s on it)\n", FUZZ_NAME,
             names[i], WTERMSIG(status), FUZZ_NAME);
      bad++;
    } else if (WEXITSTATUS(status)) {
      printf("FAIL fuzz/%s/%s: exit status %d\n", FUZZ_NAME, names[i], WEXITSTATUS(status));
      bad++;
    }
    free(names[i]);
  }
  free(names);
  if (!bad) printf("PASS fuzz/%s: %zu inputs\n", FUZZ_NAME, n);
  return 0;
}
