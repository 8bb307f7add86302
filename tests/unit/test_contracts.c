/*
** test_contracts.c: the runtime contract checks (TDS_REQUIRE, TDS_ASSERT
** in tds.h), compiled into the core the unit tests link (-DTDS_CHECKS).
**
** A broken TDS_REQUIRE is an error through the ctx (TDS_EBUG, "file:line:
** broken contract: condition") and the process goes on; a broken
** TDS_ASSERT prints the same on stderr and aborts, seen here from a
** child process.
*/
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "check.h"
#include "helpers.h"

#ifndef TDS_CHECKS
#error "test_contracts needs the checked core (-DTDS_CHECKS)"
#endif

static void *counting(void *ud, void *p, size_t n) {
  ++*(long *)ud;
  if (n == 0) {
    free(p);
    return NULL;
  }
  return realloc(p, n);
}

/* A surface whose allocator is not its context's (tds.h forbids it):
** refine is refused with TDS_EBUG naming snap.c and the condition, and the
** surface is untouched. */
static void contract_require_reports(void) {
  tds_ctx ctx;
  tds_surf s;
  h_setup(&ctx, &s);
  REQUIRE_OK(&ctx, h_cube(&ctx, &s, 1));
  REQUIRE_OK(&ctx, tds_surf_update(&ctx, &s));
  int32_t nf = s.m.nf;
  double area = s.area;
  long calls = 0;
  ctx.alloc.fn = counting;
  ctx.alloc.ud = &calls;
  int32_t n = -1;
  int rc = tds_refine(&ctx, &s, NULL, &n);
  CHECK(rc == TDS_EBUG);
  CHECK(strstr(ctx.errmsg, "snap.c:") != NULL);
  CHECK(strstr(ctx.errmsg, "broken contract: tds_alloc_same(&ctx->alloc, &s->m.alloc)") != NULL);
  CHECK(s.m.nf == nf && s.area == area && n == -1);
  CHECK(calls == 0); /* refused before anything was allocated */
  ctx.alloc = s.m.alloc; /* the same again: refine works */
  CHECK_OK(&ctx, tds_refine(&ctx, &s, NULL, &n));
  CHECK(s.m.nf == 4 * nf);
  CHECK_MESH(&ctx, &s.m);
  tds_surf_free(&s);
}

/* A facet from edges that do not chain (tds_mesh_add_facet's contract):
** the child process prints mesh.c:LINE and the condition, and aborts. */
static void contract_assert_aborts(void) {
  int fd[2];
  if (pipe(fd) != 0) {
    CHECK(!"pipe");
    return;
  }
  fflush(stdout);
  pid_t pid = fork();
  if (pid == 0) {
    dup2(fd[1], 2);
    close(fd[0]);
    tds_mesh m;
    tds_mesh_init(&m);
    const double x[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    for (int i = 0; i < 3; i++) tds_mesh_add_vertex(&m, x[i]);
    tds_mesh_add_edge(&m, 0, 1);
    tds_mesh_add_edge(&m, 1, 2);
    tds_mesh_add_edge(&m, 0, 2); /* 2 -> 0 would close the loop; 0 -> 2 does not */
    const int32_t oe[3] = {TDS_OREF(0, 0), TDS_OREF(1, 0), TDS_OREF(2, 0)};
    tds_mesh_add_facet(&m, oe);
    _exit(0); /* not reached when the check works */
  }
  close(fd[1]);
  char buf[512] = {0};
  size_t got = 0;
  ssize_t r;
  while (got < sizeof buf - 1 && (r = read(fd[0], buf + got, sizeof buf - 1 - got)) > 0)
    got += (size_t)r;
  close(fd[0]);
  int status = 0;
  CHECK(waitpid(pid, &status, 0) == pid);
  CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT);
  CHECK(strstr(buf, "mesh.c:") != NULL);
  CHECK(strstr(buf, "broken contract: tds_mesh_edges_chain(m, oe)") != NULL);
  if (check_failed_) printf("  child's stderr: %s\n", buf);
}

int main(void) {
  RUN(contract_require_reports);
  RUN(contract_assert_aborts);
  return check_done();
}
