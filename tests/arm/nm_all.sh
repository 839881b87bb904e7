#!/bin/sh
# nm for linked images, called by tests/rules/check_fw_symbols.sh as "NM -u FILE":
# an image has no undefined symbols left, so list every symbol it contains
# (the firmware rules forbid float helpers and heap functions being linked
# in at all, not just referenced).  ARM_NM selects the tool.
[ "$1" = "-u" ] && shift
exec "${ARM_NM:-arm-none-eabi-nm}" "$1"
