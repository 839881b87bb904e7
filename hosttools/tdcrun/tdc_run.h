/* tdc_run.h - modes of the tdc-run program (each in its own file). */
#ifndef TDC_RUN_H
#define TDC_RUN_H

#include "tdc_tool.h"

/* Exit codes: the shared table of every tdc program (tdc_tool.h,
 * docs/tools.md): OK, ARGS (usage), FILE (cannot read or write a file),
 * INPUT (a PNG or frame of the wrong size), REFUSED (the firmware refused
 * the frame or the configuration), NOMEM. */

/* TRM mode (default): tdc_run.c */
int tdc_run_trm_main(int argc, char **argv);
/* Tile assembly mode: `tdc-run assemble ...` (run_assemble.c) */
int tdc_run_assemble_main(int argc, char **argv);

#endif
