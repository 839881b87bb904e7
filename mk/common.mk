# The common host library, below sim/, render/ and hosttools/ (docs/design.md
# §10): the tool convention and exit-code table (tdc_tool, tdc_exit), PNG
# I/O, .tdcs stream files, LCD measurement files (tdc_meas), the LCD
# physical model's parameters and TDC_FREE_ALL (tdc_free.h); for the Python
# tools tdc_exit.py and the command-line reader tdc_argv.py.  None of
# them includes anything but firmware/ and common/ headers; the include
# direction is checked by tests/rules/check_include_dirs.py.  Archived into
# SIMLIB, so every host program and test linking that has it; tdc_meas is
# linked by name (mk/lcd.mk) into the two programs that read those files.
COMMON_SRCS := common/tdc_tool.c common/tdc_png.c common/tdc_link_file.c
SIM_SRCS += $(COMMON_SRCS)
