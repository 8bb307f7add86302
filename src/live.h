/*
** live.h: the live view's HTTP server (libmicrohttpd, its own thread).
**
** The server listens on 127.0.0.1 only and serves, read-only:
**   /, /index.html, /live.js      the page, from WEBDIR
**   /three/build/..., /three/examples/jsm/...
**                                 three.js's module files, from
**                                 WEBDIR/node_modules/three
**   /api/version                  {"version": N} of the newest snapshot
**   /api/snapshot                 the newest snapshot (live_snap.h), its
**                                 version also in header X-Tds-Version
** Everything else is 404; methods other than GET and HEAD are 405.
**
** Threads: the caller (main thread) publishes snapshots; the server thread
** only reads the newest one under the mutex. Nothing here touches a
** surface. All signals are blocked in the server's thread, so SIGINT stays
** with the thread that runs commands.
*/
#ifndef TDS_LIVE_H
#define TDS_LIVE_H

#include <stddef.h>
#include <stdint.h>

#include "tds.h"

typedef struct tds_live tds_live;

/* Start serving WEBDIR on 127.0.0.1:port (0: a free port the system
** picks). TDS_OK with *out set, TDS_EIO (port busy, cannot listen) or
** TDS_ENOMEM with a message in ctx. */
int tds_live_start(tds_ctx *ctx, const char *webdir, int port, tds_live **out);

/* The port it listens on. */
int tds_live_port(const tds_live *lv);

/* Make buf (len bytes, malloc'd, built for `version`) the newest
** snapshot; the server owns it from now on. */
void tds_live_publish(tds_live *lv, unsigned char *buf, size_t len,
                      uint64_t version);

/* Stop the server (waits for its thread) and free everything. */
void tds_live_stop(tds_live *lv);

/* A directory holding the page (index.html) and three.js
** (node_modules/three/build/three.module.js): $TDS_WEB_DIR if set, else
** web/ beside the program, one level up (build dirs), or
** ../share/tds/web (an install). exe is the program's path (may be NULL:
** /proc/self/exe). Returns a malloc'd path or NULL (message in ctx). */
char *tds_live_find_web(tds_ctx *ctx, const char *exe);

#endif
