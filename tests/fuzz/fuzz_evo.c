/*
** fuzz_evo.c: libFuzzer harness of Evolver's command language: the .tds
** harness (fuzz_tds.c, its sandbox, budgets and checks) with each input
** run as Evolver command text by `evolver(text)` on the unit cube. A
** crash, sanitizer report, broken mesh or check-mode report is a bug; an
** error message is the normal way to refuse bad text.
*/
#define FUZZ_EVOLVER 1
#include "fuzz_tds.c"
