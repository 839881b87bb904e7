# LCD panels: overdrive-aware temporal model (firmware), physical LCD
# simulation and calibration (host).  See docs/lcd.md.
#
# FW_LCD_SRCS: firmware sources only LCD panels need.  Host builds link them
# (FW_SRCS); board builds for OLED panels leave them out (mk/boards.mk).
FW_LCD_SRCS := firmware/tdc_lcd.c firmware/tdc_overdrive.c
FW_SRCS += $(FW_LCD_SRCS)
SIM_SRCS += sim/lcd/tdc_lcdsim.c sim/lcd/tdc_lcd_ref.c

# The overdrive tables are generated from the double-precision model.
$(TABLEGEN): sim/lcd/tdc_lcd_model.h firmware/tdc_lcd.h

# Host programs: the simulated Fig. 7 measurement and the calibration fit.
TDC_LCD_MEASURE := $(B)/bin/tdc-lcd-measure
TDC_CALIB := $(B)/bin/tdc-calib
HOST_PROGS += $(TDC_LCD_MEASURE) $(TDC_CALIB)
$(TDC_LCD_MEASURE): $(B)/sim/lcd/tdc_lcd_measure.o $(SIMLIB)
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $< -o $@ $(SIMLIB) -lm
$(TDC_CALIB): $(B)/hosttools/calib/tdc_calib.o
	@mkdir -p $(@D)
	$(CC) $(HOST_LDFLAGS) $< -o $@ -lm

# The calibration loop (docs/lcd.md): measure the simulated panels as paper
# Fig. 7 does, fit, write the shipped LCD profiles.  Deliberate, like
# golden-update: the profiles are committed, regenerate them only on purpose.
LCD_MEAS_FLAGS := --grid 17 --integration 1 --noise 0.002 --seed 1
lcd-profiles: $(TDC_LCD_MEASURE) $(TDC_CALIB)
	@mkdir -p $(B)/lcd
	$(TDC_LCD_MEASURE) sim/lcd/panels/pg279q.lcdsim 120,144,165 $(LCD_MEAS_FLAGS) -o $(B)/lcd/pg279q.csv
	$(TDC_CALIB) $(B)/lcd/pg279q.csv -o boards/panels/pg279q.panel --name pg279q --width 2560 --height 1440 \
	    --refresh 144 --table 33 --note "FITTED TO THE SIMULATED PANEL sim/lcd/panels/pg279q.lcdsim (ASUS PG279Q class, not a measured monitor) by make lcd-profiles"
	$(TDC_LCD_MEASURE) sim/lcd/panels/lcd-240.lcdsim 144,240 $(LCD_MEAS_FLAGS) -o $(B)/lcd/lcd-240.csv
	$(TDC_CALIB) $(B)/lcd/lcd-240.csv -o boards/panels/lcd-240.panel --name lcd-240 --width 1920 --height 1080 \
	    --refresh 240 --table 33 --note "FITTED TO THE SIMULATED PANEL sim/lcd/panels/lcd-240.lcdsim (240 Hz TN class, strobed backlight, not a measured monitor) by make lcd-profiles"
.PHONY: lcd-profiles

# The report (docs/lcd-report.md): perceived error of TRM frames on the
# simulated LCD per inverse mode, and the firmware time per 1440x1600 frame.
BENCHES += $(B)/tests/bench/bench_lcd_report
report-lcd: $(B)/tests/bench/bench_lcd_report
	$(B)/tests/bench/bench_lcd_report --panel pg279q -o docs/lcd-report.md
	$(B)/tests/bench/bench_lcd_report --panel lcd-240 -o docs/lcd-report-240.md
.PHONY: report-lcd

# Tests.
TESTS += $(B)/tests/unit/test_lcd_solve
TESTS += $(B)/tests/unit/test_lcd_sim
TESTS += $(B)/tests/unit/test_lcd_stage
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
