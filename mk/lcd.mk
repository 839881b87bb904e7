# LCD panels: overdrive-aware temporal model (firmware), physical LCD
# simulation and calibration (host).  See docs/lcd.md.
#
# FW_LCD_SRCS: firmware sources only LCD panels need.  Host builds link them
# (FW_SRCS); board builds for OLED panels leave them out (mk/boards.mk).
FW_LCD_SRCS := firmware/tdc_lcd.c firmware/tdc_lcd_state.c firmware/tdc_overdrive.c firmware/tdc_lcd_avx2.c
FW_SRCS += $(FW_LCD_SRCS)
SIM_SRCS += sim/lcd/tdc_lcdsim.c sim/lcd/tdc_lcd_ref.c

# The overdrive tables are generated from the double-precision model.
$(TABLEGEN): common/tdc_lcd_model.h firmware/tdc_lcd.h

# Host programs: the simulated Fig. 7 measurement and the calibration fit.
TDC_LCD_MEASURE := $(B)/bin/tdc-lcd-measure
TDC_CALIB := $(B)/bin/tdc-calib
HOST_PROGS += $(TDC_LCD_MEASURE) $(TDC_CALIB)
# The measurement-file reader (tdc_meas) is shared by both and the fuzz target.
TDC_MEAS_OBJ := $(B)/common/tdc_meas.o
$(TDC_LCD_MEASURE): $(B)/sim/lcd/tdc_lcd_measure.o $(TDC_MEAS_OBJ) $(SIMLIB)
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $(filter %.o,$^) -o $@ $(SIMLIB) -lm
$(TDC_CALIB): $(B)/hosttools/calib/tdc_calib.o $(B)/hosttools/calib/tdc_calib_trans.o $(TDC_MEAS_OBJ) \
              $(B)/common/tdc_tool.o
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $^ -o $@ -lm

# The calibration loop (docs/lcd.md): measure the simulated panels as paper
# Fig. 7 does, fit, write the shipped LCD profiles.  Deliberate, like
# golden-update: the profiles are committed, regenerate them only on purpose.
# Transitions (stateful tables): a 33 x 33 (previous drive, drive) grid, two
# runs of every transition so tdc-calib sees the measurement noise.
LCD_MEAS_FLAGS := --grid 17 --integration 1 --noise 0.002 --seed 1
LCD_TRANS_FLAGS := --transitions --grid 33 --runs 2 --noise 0.002 --seed 2
# lcd-240: 8 runs, 65-node tables, smoothed (the static goal, docs/lcd.md §8).
LCD_TRANS_FLAGS_240 := --transitions --grid 33 --runs 8 --noise 0.002 --seed 2
# photometry: not in the measurements (relative to white); stated with its source
LCD_PHOT_pg279q = --peak-cdm2 350 --black-cdm2 0.35 --distance-m 0.6 \
    --photometry-note "ASUS PG279Q data sheet: 350 cd/m^2, 1000:1; desk distance"
LCD_PHOT_lcd-240 = --peak-cdm2 400 --black-cdm2 0.4 --distance-m 0.6 \
    --photometry-note "assumed, not measured: a typical 240 Hz gaming LCD data sheet value, 1000:1; desk distance"
lcd-profiles: $(TDC_LCD_MEASURE) $(TDC_CALIB)
	@mkdir -p $(B)/lcd
	$(TDC_LCD_MEASURE) sim/lcd/panels/pg279q.lcdsim 120,144,165 $(LCD_MEAS_FLAGS) -o $(B)/lcd/pg279q.csv
	$(TDC_LCD_MEASURE) sim/lcd/panels/pg279q.lcdsim 120,144,165 $(LCD_TRANS_FLAGS) -o $(B)/lcd/pg279q-tr.csv
	$(TDC_CALIB) $(B)/lcd/pg279q.csv -o boards/panels/pg279q.panel --name pg279q --width 2560 --height 1440 \
	    --refresh 144 --table 33 --transitions $(B)/lcd/pg279q-tr.csv $(LCD_PHOT_pg279q) --note "FITTED TO THE SIMULATED PANEL sim/lcd/panels/pg279q.lcdsim (ASUS PG279Q class, not a measured monitor) by make lcd-profiles"
	$(TDC_LCD_MEASURE) sim/lcd/panels/lcd-240.lcdsim 144,240 $(LCD_MEAS_FLAGS) -o $(B)/lcd/lcd-240.csv
	$(TDC_LCD_MEASURE) sim/lcd/panels/lcd-240.lcdsim 144,240 $(LCD_TRANS_FLAGS_240) -o $(B)/lcd/lcd-240-tr.csv
	$(TDC_CALIB) $(B)/lcd/lcd-240.csv -o boards/panels/lcd-240.panel --name lcd-240 --width 1920 --height 1080 \
	    --refresh 240 --table 33 --transitions $(B)/lcd/lcd-240-tr.csv --state-table 65 --smooth $(LCD_PHOT_lcd-240) --note "FITTED TO THE SIMULATED PANEL sim/lcd/panels/lcd-240.lcdsim (240 Hz TN class, strobed backlight, not a measured monitor) by make lcd-profiles"
.PHONY: lcd-profiles

# The report (docs/lcd-report.md): perceived error of TRM frames on the
# simulated LCD per inverse mode, and the firmware time per 1440x1600 frame.
BENCHES += $(B)/tests/bench/bench_lcd_report
# Diagnostic (not in make bench): which cause limits the stateful tables on
# static content, docs/lcd.md §8 (make $(B)/tests/bench/bench_lcd_floor).
report-lcd: $(B)/tests/bench/bench_lcd_report
	$(B)/tests/bench/bench_lcd_report --panel pg279q -o docs/lcd-report.md
	$(B)/tests/bench/bench_lcd_report --panel lcd-240 -o docs/lcd-report-240.md
.PHONY: report-lcd

# Tests.
TESTS += $(B)/tests/unit/test_lcd_solve
TESTS += $(B)/tests/unit/test_lcd_sim
TESTS += $(B)/tests/unit/test_lcd_stage
TESTS += $(B)/tests/unit/test_lcd_state
GOLDEN_STAGES += lcd

# Compile-out check: an OLED build's object set has no LCD symbols.
LCD_OLED_PANELS = $(foreach p,$(PANELS),$(if $(filter oled,$(shell awk '$$1 == "type" { print $$2 }' boards/panels/$(p).panel)),$(p)))
LCD_OLED_OBJS = $(patsubst %.c,$(B)/%.o,$(filter-out $(FW_LCD_SRCS),$(FW_SRCS))) \
                $(foreach p,$(LCD_OLED_PANELS),$(B)/gen/tdc_panel_$(p).o)
LCD_FW_OBJS = $(patsubst %.c,$(B)/%.o,$(FW_LCD_SRCS))
$(B)/tests/unit/test_lcd_compile_out: $(FWLIB) tests/unit/test_lcd_compile_out.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/unit/test_lcd_compile_out.sh nm --oled %s --lcd %s\n' "$(LCD_OLED_OBJS)" "$(LCD_FW_OBJS)" > $@
	@chmod +x $@
TESTS += $(B)/tests/unit/test_lcd_compile_out

# The calibration loop end to end (measure -> fit -> profile -> tables -> compile).
$(B)/tests/unit/test_lcd_calib: $(TDC_LCD_MEASURE) $(TDC_CALIB) $(TABLEGEN) tests/unit/test_lcd_calib.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/unit/test_lcd_calib.sh %s %s %s "%s"\n' "$(TDC_LCD_MEASURE)" "$(TDC_CALIB)" \
	    "$(TABLEGEN)" "$(CC) $(FW_CFLAGS)" > $@
	@chmod +x $@
TESTS += $(B)/tests/unit/test_lcd_calib

# Every LCD inverse through the simulator (modes x profiles x rates x backlight, with/without TRM).
# The optimised build only: 60 simulator runs (17 s at -O2) would add minutes
# under ASan, and the stage itself runs in the sanitizer build's unit tests.
$(B)/tests/unit/test_lcd_sim_modes: $(B)/tdc-sim tests/unit/test_lcd_sim_modes.sh
	@mkdir -p $(@D)
	@printf '#!/bin/sh\nexec tests/unit/test_lcd_sim_modes.sh %s\n' "$(B)/tdc-sim" > $@
	@chmod +x $@
ifeq ($(SAN),)
TESTS += $(B)/tests/unit/test_lcd_sim_modes
endif

# The measurement reader is fuzzed as target "meas" of mk/fuzz.mk (tests/fuzz/fuzz_meas.c).
# The AVX2 run of the stateful inverse (firmware/tdc_lcd_avx2.c): built with
# vector registers; its machine code is checked for floating point instead.
$(B)/firmware/tdc_lcd_avx2.o: FW_CFLAGS := $(filter-out -mgeneral-regs-only,$(FW_CFLAGS))
