/* repl.h: the interactive loop and chunk execution shared with main. */
#ifndef TDS_REPL_H
#define TDS_REPL_H

#include "lua_tds.h"

/* Run the function on top of the stack (popped) with Ctrl-C support.
** Returns 0 on success; otherwise prints the error to stderr and returns 1,
** or 2 if the chunk called q() (exit code in *quit_code). */
int tds_run_chunk(lua_State *L, tds_state *st, int *quit_code);
/* The same; an error message without a position (raised by C code) gets
** the innermost user code's "file:line: ", else where (if not NULL). */
int tds_run_chunk_at(lua_State *L, tds_state *st, int *quit_code, const char *where);

/* The REPL: reads lines (readline on a terminal, plain lines otherwise)
** until end of input or q(). Returns the exit code: 0, or the q() code,
** or 1 if reading stdin (not a terminal) met an error in any chunk. */
int tds_repl(lua_State *L, tds_state *st);

#endif
