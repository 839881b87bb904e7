/* tdc_run.h - modes of the tdc-run program (each in its own file). */
#ifndef TDC_RUN_H
#define TDC_RUN_H

/* Exit codes shared by every mode. */
enum {
    TDC_RUN_EXIT_OK = 0,
    TDC_RUN_EXIT_FAILED = 1, /* bad input file, size mismatch, firmware refused */
    TDC_RUN_EXIT_USAGE = 2   /* wrong options */
};

/* TRM mode (default): tdc_run.c */
int tdc_run_trm_main(int argc, char **argv);
/* Tile assembly mode: `tdc-run assemble ...` (run_assemble.c) */
int tdc_run_assemble_main(int argc, char **argv);

#endif
