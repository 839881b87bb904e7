#!/bin/sh
# make test-vm: boots Debian's kernel (linux-image-amd64) under
# qemu-system-x86_64 with TCG (no KVM) and a busybox initramfs that runs
# tests/vm/init.sh: tdc-usb against dummy_hcd + a FunctionFS gadget running
# the firmware's USB protocol code, tdc-gpio against gpio-sim (built here as
# an out-of-tree module from Debian's linux-source).
# The Linux board (tdc-board, BOARD=linux) runs there too, on Debian's
# bochs DRM driver and QEMU's bochs-display; its scan-out is captured from
# outside (tests/vm/qemu_capture.py) and compared byte for byte with the
# host loop's frames (tests/vm/display_data.sh).
# Usage: tests/vm/run-vm.sh BIN_DIR VM_DIR BOARD HOST_LOOP W H HZ BOARD2 NAME=STREAM...
#   BIN_DIR: directory with tdc-usb, tdc-gpio, tdc_ffs_board, tdc_vsync_gen, tdc_vm_mkstream
#   VM_DIR:  work directory (module build, initramfs, console log)
#   BOARD:   the Linux board program for a W x H (all eyes) HZ panel, HOST_LOOP
#            the host double of its frame loop, NAME=STREAM the streams shown,
#            BOARD2 the board for a panel the VM's display has no mode for
set -eu
bin=$1; vm=$2; tdcb=$3; hostloop=$4; dw=$5; dh=$6; rate=$(($7 * 1000)); tdcb2=$8
shift 8
mkdir -p "$vm"

need() { command -v "$1" > /dev/null 2>&1 || { echo "test-vm: missing $1 ($2)"; exit 1; }; }
need qemu-system-x86_64 "Debian package qemu-system-x86"
need cpio "Debian package cpio"
[ -x /bin/busybox ] && ldd /bin/busybox 2>&1 | grep -q 'not a dynamic' \
    || { echo "test-vm: missing static /bin/busybox (Debian package busybox-static)"; exit 1; }

# The kernel linux-image-amd64 points to, its headers and its source.
kpkg=$(dpkg-query -W -f='${Depends}' linux-image-amd64 2>/dev/null | sed -n 's/^\(linux-image-[^ ,]*\).*/\1/p')
kver=${kpkg#linux-image-}
[ -n "$kver" ] && [ -r "/boot/vmlinuz-$kver" ] || { echo "test-vm: no kernel (Debian package linux-image-amd64)"; exit 1; }
[ -d "/lib/modules/$kver/build" ] || { echo "test-vm: no headers for $kver (linux-headers-amd64)"; exit 1; }
src=$(ls /usr/src/linux-source-*.tar.xz 2>/dev/null | tail -n 1)
[ -n "$src" ] || { echo "test-vm: no /usr/src/linux-source-*.tar.xz (Debian package linux-source)"; exit 1; }

# gpio-sim is not built in Debian's kernel: build it with irq_sim as one
# module.  The one change: irq_sim.c calls handle_simple_irq(irq_to_desc())
# and irq_to_desc is not exported to modules; generic_handle_irq() is, and
# runs the same flow handler.
ko=$vm/gpio-sim/gpio-sim.ko
if [ ! -f "$ko" ] || [ "$src" -nt "$ko" ]; then
    rm -rf "$vm/gpio-sim"; mkdir -p "$vm/gpio-sim"
    echo "test-vm: extracting gpio-sim from $src"
    tar -xJf "$src" -C "$vm/gpio-sim" --strip-components=3 --wildcards \
        '*/drivers/gpio/gpio-sim.c' '*/drivers/gpio/gpiolib.h'
    tar -xJf "$src" -C "$vm/gpio-sim" --strip-components=3 --wildcards '*/kernel/irq/irq_sim.c'
    mv "$vm/gpio-sim/gpio-sim.c" "$vm/gpio-sim/gpio-sim-main.c"
    sed -i 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' "$vm/gpio-sim/irq_sim.c"
    grep -q 'generic_handle_irq(irqnum);' "$vm/gpio-sim/irq_sim.c" \
        || { echo "test-vm: irq_sim.c changed upstream; patch does not apply"; exit 1; }
    printf 'obj-m := gpio-sim.o\ngpio-sim-y := gpio-sim-main.o irq_sim.o\n' > "$vm/gpio-sim/Kbuild"
    make -s -C "/lib/modules/$kver/build" M="$(cd "$vm/gpio-sim" && pwd)" modules
fi

# initramfs
root=$vm/root
rm -rf "$root"
mkdir -p "$root/bin" "$root/usr/bin" "$root/lib/modules" "$root/proc" "$root/sys" "$root/dev" "$root/tmp"
cp /bin/busybox "$root/bin/busybox"
ln -s busybox "$root/bin/sh"
for m in configfs usb-common usbcore udc-core libcomposite usb_f_fs dummy_hcd \
         drm drm_kms_helper ttm drm_ttm_helper drm_vram_helper bochs; do
    cp "$(modinfo -k "$kver" -n $m)" "$root/lib/modules/$m.ko"
done
cp "$ko" "$root/lib/modules/gpio-sim.ko"
for p in tdc-usb tdc-gpio tdc_ffs_board tdc_vsync_gen; do cp "$bin/$p" "$root/usr/bin/"; done
cp "$tdcb" "$root/usr/bin/tdc-board"
cp "$tdcb2" "$root/usr/bin/tdc-board-nomode"
# the launcher (A/B slots with roll-back) and the update image's program
# (stripped: 2.1 -> ~1.2 MB of DFU transfer)
cp boards/linux/tdc-board-launch "$root/usr/bin/tdc-board-launch"
mkdir -p "$root/data"
strip -o "$root/data/tdc-board-update" "$tdcb"
# Debian's dfu-util (an independent DFU client, package dfu-util) as it is
need dfu-util "Debian package dfu-util"
cp "$(command -v dfu-util)" "$root/usr/bin/dfu-util"
# shared libraries of the dynamically linked tools, at their own paths
for lib in $(ldd "$bin/tdc-usb" "$bin/tdc-gpio" "$root/usr/bin/dfu-util" | awk '/=> \//{print $3} /^\t\/lib/{print $1}' | sort -u); do
    mkdir -p "$root$(dirname "$lib")"; cp -L "$lib" "$root$lib"
done
mkdir -p "$root/lib64"; cp -L /lib64/ld-linux-x86-64.so.2 "$root/lib64/"
mkdir -p "$root/data"
"$bin/tdc_vm_mkstream" "$root/data"
tests/vm/display_data.sh "$hostloop" "$vm/expected" "$root/data/disp" "$@"
cp tests/vm/init.sh "$root/init"; chmod +x "$root/init"
(cd "$root" && find . | cpio -o -H newc --quiet) | gzip -1 > "$vm/initramfs.gz"

# The whole VM is bounded at 1800 s (qemu_capture.py kills QEMU): 126 s
# on a quiet host, 425-550 s seen at load average 15-20.
# no_timer_check: on a loaded host, TCG runs the guest so slowly that the
# kernel's early IO-APIC timer check fails and it panics ("IO-APIC + timer
# doesn't work!", seen at load average 29); the check only guards against
# broken real hardware.
echo "test-vm: booting $kver (qemu TCG) ..."
start=$(date +%s)
rm -rf "$vm/shots"
# bochs-display: the KMS device (64 MiB VRAM: fbdev's buffer and the board's
# two XRGB8888 buffers), its EDID offering the panel's size; ttyS1 carries
# the host's answers to the guest's capture requests.
/usr/bin/python3 tests/vm/qemu_capture.py "$vm/console.log" "$vm/shots" "$vm/qmp.sock" "$vm/ack.sock" 1800 -- \
    qemu-system-x86_64 -accel tcg -m 1536 -smp 1 -nographic -no-reboot -vga none \
    -device bochs-display,xres=$dw,yres=$dh,xmax=$dw,ymax=$dh,vgamem=64M,refresh_rate=$rate \
    -qmp "unix:$vm/qmp.sock,server=on,wait=off" \
    -chardev "socket,id=ack,path=$vm/ack.sock,server=on,wait=off" -serial mon:stdio -serial chardev:ack \
    -kernel "/boot/vmlinuz-$kver" -initrd "$vm/initramfs.gz" \
    -append "console=ttyS0 panic=-1 loglevel=3 no_timer_check rdinit=/init${TDC_VM_ONLY:+ tdc_only=$TDC_VM_ONLY}" || true
end=$(date +%s)
# the captured scan-out against the host loop's frames, byte for byte
: > "$vm/display.results"
for spec in "$@"; do
    name=${spec%%=*}
    # the frames the guest played (init.sh plays a prefix of some streams)
    for shot in $(sed -n 's/^VMSHOT '"$name"' \([0-9]*\).*/\1/p' "$vm/console.log" | tr -d '\r'); do
        got=$vm/shots/$name-$shot.ppm; want=$vm/expected/$name/shown-$shot.ppm
        if [ ! -f "$got" ]; then echo "VMTEST display-$name-frame$shot FAIL: not captured"
        elif cmp -s "$got" "$want"; then echo "VMTEST display-$name-frame$shot PASS"
        else echo "VMTEST display-$name-frame$shot FAIL: scan-out differs from the host loop's frame ($(cmp "$got" "$want" 2>&1 | head -c 200))"; fi
    done >> "$vm/display.results"
done
# captures of re-played streams (NAME.TAG-K.ppm): the frames of stream NAME
for got in "$vm"/shots/*.*-*.ppm; do
    [ -f "$got" ] || continue
    b=${got##*/}; b=${b%.ppm}; k=${b##*-}; tag=${b%-*}; name=${tag%%.*}
    if cmp -s "$got" "$vm/expected/$name/shown-$k.ppm"; then echo "VMTEST display-$tag-frame$k PASS"
    else echo "VMTEST display-$tag-frame$k FAIL: scan-out differs from the host loop's frame"; fi >> "$vm/display.results"
done
grep -a -E '^ *(VMTEST|    )' "$vm/console.log" | tr -d '\r' || true
cat "$vm/display.results"
echo "test-vm: $((end-start)) s, console log: $vm/console.log"
dfail=$(grep -c FAIL "$vm/display.results" || true)
res=$(grep -a 'VMTEST-DONE' "$vm/console.log" | tr -d '\r' | tail -n 1)
case "$res" in
    *"fail=0"*) [ "$dfail" = 0 ] && { echo "test-vm: $res, display captures: $(grep -c PASS "$vm/display.results") identical"; exit 0; }
                echo "test-vm: $res, but $dfail display captures differ"; exit 1 ;;
    "") echo "test-vm: the VM did not finish (see $vm/console.log)"; exit 1 ;;
    *) echo "test-vm: $res"; exit 1 ;;
esac
