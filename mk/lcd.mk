# LCD panels: overdrive-aware temporal model (firmware), physical LCD
# simulation and calibration (host).  See docs/lcd.md.
#
# FW_LCD_SRCS: firmware sources only LCD panels need.  Host builds link them
# (FW_SRCS); board builds for OLED panels leave them out (mk/boards.mk).
FW_LCD_SRCS := firmware/tdc_lcd.c firmware/tdc_overdrive.c
FW_SRCS += $(FW_LCD_SRCS)
# SIM_SRCS added below once the files exist

# The overdrive tables are generated from the double-precision model.
$(TABLEGEN): sim/lcd/tdc_lcd_model.h firmware/tdc_lcd.h
