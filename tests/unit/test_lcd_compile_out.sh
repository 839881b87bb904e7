#!/bin/sh
# The LCD inverse is compiled out of OLED builds (docs/design.md §3, issue 3).
#
# 1. Host object set of an OLED build: every firmware object except
#    $(FW_LCD_SRCS), plus the OLED panels' generated tables.  None of them may
#    define or reference a tdc_lcd_* / tdc_od_* symbol (so an OLED image
#    links without the LCD sources).  Positive control: the LCD objects do
#    define tdc_lcd_frame and tdc_od_lookup (the grep below would see them).
# 2. Linked board images, where the board build has made them
#    (build/<board>-<panel>/tdc-firmware.elf, mk/boards.mk): OLED images must
#    have no tdc_lcd_ / tdc_od_ symbol; LCD images with the LCD stage must.
#    Images are optional here (make test-arm builds them); the host object
#    check always runs.
# Usage: tests/unit/test_lcd_compile_out.sh NM --oled obj... --lcd obj...
nm_tool=$1; shift
[ "$1" = "--oled" ] || { echo "usage: $0 NM --oled obj... --lcd obj..."; exit 2; }
shift
oled=""; lcd=""; mode=oled
for a in "$@"; do
    if [ "$a" = "--lcd" ]; then mode=lcd; continue; fi
    if [ $mode = oled ]; then oled="$oled $a"; else lcd="$lcd $a"; fi
done
fail=0
n=0
for o in $oled; do
    n=$((n+1))
    bad=$("$nm_tool" "$o" 2>/dev/null | awk '$NF ~ /^tdc_(lcd|od)_/ { print $NF }' | sort -u | tr '\n' ' ')
    if [ -n "$bad" ]; then echo "compile-out: OLED build object $o has LCD symbols: $bad"; fail=1; fi
done
echo "compile-out: $n OLED-build objects, no tdc_lcd_/tdc_od_ symbol defined or referenced"
for want in tdc_lcd_frame tdc_od_lookup tdc_lcd_solve_q16; do
    if ! "$nm_tool" $lcd 2>/dev/null | awk '$2 == "T" { print $3 }' | grep -qx "$want"; then
        echo "compile-out: positive control failed: $want not defined by the LCD objects ($lcd)"; fail=1
    fi
done
[ $fail -eq 0 ] && echo "compile-out: positive control: the LCD objects define tdc_lcd_frame, tdc_od_lookup, tdc_lcd_solve_q16"
# Linked board images, if the board build has produced any.
arm_nm=arm-none-eabi-nm
imgs=0
for img in build/*/tdc-firmware.elf; do
    [ -f "$img" ] || continue
    command -v $arm_nm >/dev/null 2>&1 || break
    dir=$(basename "$(dirname "$img")")
    panel_type=""
    for p in boards/panels/*.panel; do
        name=$(basename "$p" .panel)
        case "$dir" in *-"$name"|*-"$name"-*) panel_type=$(awk '$1 == "type" { print $2 }' "$p");; esac
    done
    [ -n "$panel_type" ] || continue
    cnt=$($arm_nm "$img" | awk '$NF ~ /^tdc_(lcd|od)_/' | wc -l)
    imgs=$((imgs+1))
    if [ "$panel_type" = oled ] && [ "$cnt" -ne 0 ]; then
        echo "compile-out: OLED image $img links $cnt LCD symbols"; fail=1
    else
        echo "compile-out: image $img ($panel_type panel): $cnt tdc_lcd_/tdc_od_ symbols"
    fi
done
[ $imgs -eq 0 ] && echo "compile-out: no board images built yet (make test-arm builds them); host objects checked"
exit $fail
