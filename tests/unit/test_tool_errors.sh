#!/bin/sh
# Error paths of tdc-linkdump, tdc-render and the table generator (issue 19,
# docs/tools.md): each bad input gets one "tool: ...: why" line and its named
# exit code, nothing is written outside the folder named, an existing output
# survives a failed run.  In the ASan build the tools run with LeakSanitizer
# on, so an error path that leaks fails here.
# Usage: tests/unit/test_tool_errors.sh BUILD_DIR TABLEGEN
b=$1; tablegen=$2
. tests/unit/tool_expect.sh
render=$b/tdc-render; dump=$b/tdc-linkdump

# ---- tdc-linkdump
"$render" --builtin fence --frames 0:4 --size 32x16 --mode trm --stream "$t/s.tdcs" --quiet > /dev/null 2>&1 \
    || bad "tdc-render wrote no stream"
expect 0 "linkdump: clean stream" "" -- "$dump" "$t/s.tdcs"
n=$(wc -c < "$t/s.tdcs")
head -c $((n - 100)) "$t/s.tdcs" > "$t/cut.tdcs"
expect 13 "linkdump: file cut mid-packet is not clean" "tdc-linkdump: $t/cut.tdcs: the file ends inside a packet" -- "$dump" "$t/cut.tdcs"
{ cat "$t/s.tdcs"; printf 'trailing garbage'; } > "$t/tail.tdcs"
expect 13 "linkdump: garbage after the last packet" "ends inside a packet or with garbage (16 bytes)" -- "$dump" "$t/tail.tdcs"
printf 'not a stream at all, not at all' > "$t/junk.tdcs"
expect 13 "linkdump: not a stream" "junk.tdcs: not a .tdcs stream: it does not start with a valid STREAM packet" -- "$dump" "$t/junk.tdcs"
expect 7 "linkdump: missing file" "nope.tdcs: cannot open for reading: No such file" -- "$dump" "$t/nope.tdcs"
expect 1 "linkdump: usage" "usage" -- "$dump"

# ---- tdc-render
mkdir -p "$t/png"
printf 'tdc-scene 1\nname ../escaped\n' > "$t/esc.scene"
expect 13 "render: scene name '../escaped' refused" "scene name '../escaped'" -- "$render" --scene "$t/esc.scene" --png "$t/png"
[ ! -e "$t/escaped-full-0000.png" ] && ok "render: nothing written outside --png DIR" || bad "render: wrote outside DIR"
# a scene file in a sub-folder and no name line: its base name names the files
mkdir -p "$t/sub"
"$render" --print-scene fence | sed '/^name /d' > "$t/sub/my.scene"
expect 0 "render: scene path with '/' and no name" "" -- "$render" --scene "$t/sub/my.scene" --png "$t/png" --size 16x8 --quiet
[ -e "$t/png/my-full-0000.png" ] && ok "render: named after the file's base name" || bad "render: no $t/png/my-full-0000.png ($(ls "$t/png"))"
expect 1 "render: --frames wrap refused" "bad value for --frames '4294967297:4294967298'" -- "$render" --builtin fence --frames 4294967297:4294967298
expect 1 "render: --size wrap refused" "bad value for --size" -- "$render" --builtin fence --size 4294967312x16
expect 1 "render: --reduced-factor nan refused" "bad value for --reduced-factor 'nan'" -- "$render" --builtin fence --reduced-factor nan
expect 1 "render: unknown built-in" "unknown built-in scene" -- "$render" --builtin nosuch
expect 7 "render: missing scene file" "" -- "$render" --scene "$t/nope.scene"
printf 'tdc-scene 1\nbogus line\n' > "$t/bad.scene"
expect 13 "render: bad scene line" "bad.scene:2" -- "$render" --scene "$t/bad.scene"
expect 7 "render: stream into a missing folder" "" -- "$render" --builtin fence --size 16x8 --stream "$t/no/dir/x.tdcs" --quiet

# ---- tdc-sim: option numbers (ARGS = 1)
sim=$b/tdc-sim
expect 1 "sim: -r nan refused as the option" "bad refresh 'nan'" -- "$sim" -r nan
expect 1 "sim: -r inf refused" "bad refresh 'inf'" -- "$sim" -r inf
expect 1 "sim: -g 2^32+32 x 24 refused, not 32x24" "bad size '4294967328x24'" -- "$sim" -g 4294967328x24
expect 1 "sim: -m '' refused as the option" "bad mode list ''" -- "$sim" -m ""

# ---- the table generator
mkdir -p "$t/gen"
"$tablegen" boards/panels/htc-vive.panel "$t/gen" || bad "tablegen: good profile"
cp "$t/gen/tdc_panel_htc-vive.c" "$t/keep.c"
{ cat boards/panels/htc-vive.panel; printf '# %0600d width 7\n' 0; } > "$t/htc-vive.panel"
expect 13 "tablegen: a 600-byte line is refused with its number" "htc-vive.panel:$(($(wc -l < boards/panels/htc-vive.panel) + 1)): line longer than 511" -- "$tablegen" "$t/htc-vive.panel" "$t/gen"
{ cat boards/panels/htc-vive.panel; echo 'refresh_hz 4294967386'; } > "$t/htc-vive.panel"
expect 13 "tablegen: refresh_hz 2^32+90 refused" "refresh_hz: expected an integer" -- "$tablegen" "$t/htc-vive.panel" "$t/gen"
{ cat boards/panels/htc-vive.panel; echo 'gamma nan 2.2 2.2'; } > "$t/htc-vive.panel"
expect 13 "tablegen: gamma nan refused" "gamma: expected a number" -- "$tablegen" "$t/htc-vive.panel" "$t/gen"
{ cat boards/panels/htc-vive.panel; echo 'black_cdm2 99'; echo 'peak_cdm2 50'; } > "$t/htc-vive.panel"
expect 13 "tablegen: black above peak refused" "black_cdm2 99 must be below peak_cdm2 50" -- "$tablegen" "$t/htc-vive.panel" "$t/gen"
{ cat boards/panels/htc-vive.panel; echo 'peak_cdm2 0'; } > "$t/htc-vive.panel"
expect 13 "tablegen: peak_cdm2 0 refused" "peak_cdm2: expected a number" -- "$tablegen" "$t/htc-vive.panel" "$t/gen"
cmp -s "$t/gen/tdc_panel_htc-vive.c" "$t/keep.c" && ok "tablegen: the existing table survives failed runs" || bad "tablegen: table changed"
expect 7 "tablegen: missing profile" "cannot open" -- "$tablegen" "$t/nope.panel" "$t/gen"
expect 7 "tablegen: missing output folder" "cannot write" -- "$tablegen" boards/panels/htc-vive.panel "$t/no/dir"
expect 1 "tablegen: usage" "usage" -- "$tablegen"
ls "$t/gen" | grep -q tmp && bad "tablegen: temporary left behind" || ok "tablegen: no temporary left behind"

echo "tool errors: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
