#!/bin/sh
# make test-vm, display part, host side before the boot: for each stream,
# the frames the Linux board must show (the host double of the frame loop,
# built for the board's panel and stages, dumps them as PPM) and the stream
# cut at the frame boundaries the host double saw, so the VM can send it
# piece by piece and have the scan-out captured after each shown frame.
# Usage: display_data.sh HOST_LOOP OUT_HOST OUT_GUEST NAME=STREAM.tdcs...
#   OUT_HOST/NAME/shown-K.ppm   expected frames (stay on the host)
#   OUT_GUEST/NAME/part-I       stream pieces (go into the initramfs)
#   OUT_GUEST/NAME/plan         lines "part-I FRAMES SHOT": after sending
#                               part-I the board has shown FRAMES more
#                               frames; SHOT: the index of the expected frame
#                               then on screen, or - (none new)
set -eu
loop=$1; out=$2; guest=$3; shift 3
for spec in "$@"; do
    name=${spec%%=*}; stream=${spec#*=}
    d=$out/$name; g=$guest/$name
    rm -rf "$d" "$g"; mkdir -p "$d" "$g"
    "$loop" "$stream" "$d" > "$d/checksums" 2> "$d/log" || { echo "display_data: host loop failed on $stream"; cat "$d/log"; exit 1; }
    size=$(stat -c %s "$stream")
    # frames shown at the same read end form one piece; only its last is captured
    awk -v size="$size" '
        $2 == "end" { next }
        { if ($2 == last) { n[k]++; shot[k] = $1 } else { k++; off[k] = $2; n[k] = 1; shot[k] = $1; last = $2 } }
        END { prev = 0
              for (i = 1; i <= k; i++) { printf "%d %d %d %s\n", prev, off[i] - prev, n[i], shot[i]; prev = off[i] }
              if (prev < size) printf "%d %d 0 -\n", prev, size - prev }' "$d/offsets" > "$d/cuts"
    : > "$g/plan"
    i=0
    while read -r from len frames shot; do
        dd if="$stream" of="$g/part-$i" iflag=skip_bytes,count_bytes skip="$from" count="$len" bs=1M status=none
        echo "part-$i $frames $shot" >> "$g/plan"
        i=$((i + 1))
    done < "$d/cuts"
    # the pieces are the stream, byte for byte
    for p in $(awk '{ print $1 }' "$g/plan"); do cat "$g/$p"; done | cmp -s - "$stream" \
        || { echo "display_data: pieces of $name differ from $stream"; exit 1; }
    echo "display_data: $name: $(grep -c . "$d/checksums") frames, $(grep -c . "$g/plan") pieces"
done
