/* live.c: the live view's HTTP server (see live.h). */
#include "live.h"

#include <arpa/inet.h>
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <microhttpd.h>
#include <netinet/in.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

struct tds_live {
  struct MHD_Daemon *d;
  pthread_mutex_t mu;
  unsigned char *snap; /* newest snapshot, or NULL before the first */
  size_t snap_len;
  uint64_t version;
  int port;
  char *webdir;
};

static enum MHD_Result reply(struct MHD_Connection *c, unsigned status,
                             struct MHD_Response *r, const char *type) {
  if (!r) return MHD_NO;
  if (type) MHD_add_response_header(r, MHD_HTTP_HEADER_CONTENT_TYPE, type);
  MHD_add_response_header(r, MHD_HTTP_HEADER_CACHE_CONTROL, "no-store");
  enum MHD_Result ok = MHD_queue_response(c, status, r);
  MHD_destroy_response(r);
  return ok;
}

static enum MHD_Result text(struct MHD_Connection *c, unsigned status,
                            const char *msg) {
  struct MHD_Response *r = MHD_create_response_from_buffer(
      strlen(msg), (void *)(uintptr_t)msg, MHD_RESPMEM_MUST_COPY);
  return reply(c, status, r, "text/plain; charset=utf-8");
}

static const char *mime(const char *path) {
  const char *dot = strrchr(path, '.');
  if (dot && !strcmp(dot, ".html")) return "text/html; charset=utf-8";
  if (dot && !strcmp(dot, ".js")) return "text/javascript; charset=utf-8";
  if (dot && !strcmp(dot, ".css")) return "text/css; charset=utf-8";
  if (dot && !strcmp(dot, ".json")) return "application/json";
  return "application/octet-stream";
}

/* A file below the web dir; rel has no "..", "//" or leading "/". */
static enum MHD_Result file(struct MHD_Connection *c, const tds_live *lv,
                            const char *rel) {
  char path[PATH_MAX];
  if (snprintf(path, sizeof path, "%s/%s", lv->webdir, rel) >= (int)sizeof path)
    return text(c, MHD_HTTP_NOT_FOUND, "not found\n");
  int fd = open(path, O_RDONLY | O_CLOEXEC);
  struct stat sb;
  if (fd < 0) return text(c, MHD_HTTP_NOT_FOUND, "not found\n");
  if (fstat(fd, &sb) != 0 || !S_ISREG(sb.st_mode)) {
    close(fd);
    return text(c, MHD_HTTP_NOT_FOUND, "not found\n");
  }
  struct MHD_Response *r = MHD_create_response_from_fd((uint64_t)sb.st_size, fd);
  if (!r) close(fd);
  return reply(c, MHD_HTTP_OK, r, mime(rel));
}

/* Only plain names: letters, digits, '_', '-', '.', separated by single
** '/', no component starting with '.'. */
static int safe_path(const char *p) {
  if (!*p) return 0;
  for (const char *s = p; *s; s++) {
    if (*s == '/' && (s[1] == '/' || s[1] == 0)) return 0;
    if ((s == p || s[-1] == '/') && *s == '.') return 0;
    if (!(isalnum((unsigned char)*s) || *s == '_' || *s == '-' || *s == '.' || *s == '/'))
      return 0;
  }
  return 1;
}

static enum MHD_Result handle(void *cls, struct MHD_Connection *c,
                              const char *url, const char *method,
                              const char *version, const char *upload,
                              size_t *upload_size, void **con_cls) {
  (void)version;
  (void)upload;
  (void)con_cls;
  tds_live *lv = cls;
  /* Only pages of this server itself: a Host other than the loopback
  ** address (a DNS-rebinding page) gets nothing. */
  const char *host = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Host");
  char want[2][32];
  pthread_mutex_lock(&lv->mu);
  int port = lv->port;
  pthread_mutex_unlock(&lv->mu);
  snprintf(want[0], sizeof want[0], "127.0.0.1:%d", port);
  snprintf(want[1], sizeof want[1], "localhost:%d", port);
  if (host && strcmp(host, want[0]) != 0 && strcmp(host, want[1]) != 0)
    return text(c, MHD_HTTP_FORBIDDEN, "forbidden host\n");
  if (strcmp(method, "GET") != 0 && strcmp(method, "HEAD") != 0)
    return text(c, MHD_HTTP_METHOD_NOT_ALLOWED, "method not allowed\n");
  if (*upload_size) return text(c, MHD_HTTP_BAD_REQUEST, "unexpected body\n");
  if (!strcmp(url, "/") || !strcmp(url, "/index.html"))
    return file(c, lv, "index.html");
  if (!strcmp(url, "/live.js")) return file(c, lv, "live.js");
  if (!strncmp(url, "/three/", 7)) {
    const char *rel = url + 7;
    if ((strncmp(rel, "build/", 6) && strncmp(rel, "examples/jsm/", 13)) ||
        !safe_path(rel))
      return text(c, MHD_HTTP_NOT_FOUND, "not found\n");
    char path[PATH_MAX];
    snprintf(path, sizeof path, "node_modules/three/%s", rel);
    return file(c, lv, path);
  }
  if (!strcmp(url, "/api/version")) {
    char buf[64];
    pthread_mutex_lock(&lv->mu);
    snprintf(buf, sizeof buf, "{\"version\":%llu}\n",
             (unsigned long long)lv->version);
    pthread_mutex_unlock(&lv->mu);
    struct MHD_Response *r = MHD_create_response_from_buffer(
        strlen(buf), buf, MHD_RESPMEM_MUST_COPY);
    return reply(c, MHD_HTTP_OK, r, "application/json");
  }
  if (!strcmp(url, "/api/snapshot")) {
    struct MHD_Response *r = NULL;
    char ver[32];
    pthread_mutex_lock(&lv->mu);
    if (lv->snap)
      r = MHD_create_response_from_buffer(lv->snap_len, lv->snap,
                                          MHD_RESPMEM_MUST_COPY);
    snprintf(ver, sizeof ver, "%llu", (unsigned long long)lv->version);
    int have = lv->snap != NULL;
    pthread_mutex_unlock(&lv->mu);
    if (!have) return text(c, MHD_HTTP_SERVICE_UNAVAILABLE, "no snapshot yet\n");
    if (r) MHD_add_response_header(r, "X-Tds-Version", ver);
    return reply(c, MHD_HTTP_OK, r, "application/octet-stream");
  }
  return text(c, MHD_HTTP_NOT_FOUND, "not found\n");
}

int tds_live_start(tds_ctx *ctx, const char *webdir, int port, tds_live **out) {
  if (port < 0 || port > 65535)
    return tds_seterr(ctx, TDS_ERANGE, "live view: port %d is not 0..65535", port);
  tds_live *lv = calloc(1, sizeof *lv);
  if (!lv || !(lv->webdir = strdup(webdir))) {
    free(lv);
    return tds_seterr(ctx, TDS_ENOMEM, "live view: out of memory");
  }
  pthread_mutex_init(&lv->mu, NULL);
  lv->port = port;
  struct sockaddr_in sa;
  memset(&sa, 0, sizeof sa);
  sa.sin_family = AF_INET;
  sa.sin_port = htons((uint16_t)port);
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  /* The server thread inherits the signal mask: block everything there. */
  sigset_t all, old;
  sigfillset(&all);
  pthread_sigmask(SIG_SETMASK, &all, &old);
  lv->d = MHD_start_daemon(MHD_USE_AUTO_INTERNAL_THREAD, (uint16_t)port, NULL,
                           NULL, handle, lv, MHD_OPTION_SOCK_ADDR, &sa,
                           MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)30,
                           MHD_OPTION_CONNECTION_LIMIT, (unsigned)64,
                           MHD_OPTION_END);
  int err = errno;
  pthread_sigmask(SIG_SETMASK, &old, NULL);
  if (!lv->d) {
    pthread_mutex_destroy(&lv->mu);
    free(lv->webdir);
    free(lv);
    if (port)
      return tds_seterr(ctx, TDS_EIO, "live view: cannot listen on 127.0.0.1:%d (%s)",
                        port, err == EADDRINUSE ? "port in use" : strerror(err));
    return tds_seterr(ctx, TDS_EIO, "live view: cannot start the server (%s)",
                      strerror(err));
  }
  const union MHD_DaemonInfo *info =
      MHD_get_daemon_info(lv->d, MHD_DAEMON_INFO_BIND_PORT);
  pthread_mutex_lock(&lv->mu);
  lv->port = info ? info->port : port;
  pthread_mutex_unlock(&lv->mu);
  *out = lv;
  return TDS_OK;
}

int tds_live_port(const tds_live *lv) { return lv->port; }

void tds_live_publish(tds_live *lv, unsigned char *buf, size_t len,
                      uint64_t version) {
  pthread_mutex_lock(&lv->mu);
  unsigned char *old = lv->snap;
  lv->snap = buf;
  lv->snap_len = len;
  lv->version = version;
  pthread_mutex_unlock(&lv->mu);
  free(old);
}

void tds_live_stop(tds_live *lv) {
  if (!lv) return;
  MHD_stop_daemon(lv->d);
  pthread_mutex_destroy(&lv->mu);
  free(lv->snap);
  free(lv->webdir);
  free(lv);
}

/* Nonzero when dir holds the page and three.js. */
static int web_ok(const char *dir) {
  char p[PATH_MAX + 64];
  snprintf(p, sizeof p, "%s/index.html", dir);
  if (access(p, R_OK) != 0) return 0;
  snprintf(p, sizeof p, "%s/node_modules/three/build/three.module.js", dir);
  return access(p, R_OK) == 0;
}

char *tds_live_find_web(tds_ctx *ctx, const char *exe) {
  const char *env = getenv("TDS_WEB_DIR");
  if (env && *env) {
    if (web_ok(env)) return strdup(env);
    tds_seterr(ctx, TDS_EIO, "live view: TDS_WEB_DIR=%s has no index.html and "
               "node_modules/three (run `make web` in the source tree)", env);
    return NULL;
  }
  char self[PATH_MAX];
  const char *path = exe;
  if (!path) {
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    if (n <= 0) n = 0;
    self[n] = 0;
    path = self;
  }
  char dir[PATH_MAX];
  snprintf(dir, sizeof dir, "%s", path);
  char *slash = strrchr(dir, '/');
  if (slash)
    *slash = 0;
  else
    snprintf(dir, sizeof dir, ".");
  static const char *const rel[] = {"web", "../web", "../share/tds/web"};
  for (int i = 0; i < 3; i++) {
    char cand[PATH_MAX + 32];
    snprintf(cand, sizeof cand, "%s/%s", dir, rel[i]);
    if (web_ok(cand)) return strdup(cand);
  }
  tds_seterr(ctx, TDS_EIO, "live view: page files not found in %s/web, %s/../web "
             "or %s/../share/tds/web (run `make web`, or set TDS_WEB_DIR)",
             dir, dir, dir);
  return NULL;
}
