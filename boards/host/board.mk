# Native host build: the firmware library linked into the simulator, tests
# and tdc-run.  No image, no linker script.
BOARD_DESC := native host (x86-64 / any): simulator, tests and tools
