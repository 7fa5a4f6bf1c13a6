#!/bin/sh
# firmware/run-qemu.sh --bus URL [--memory FILE]
#
# Builds the reference arbitrator firmware if needed (make), starts it on QEMU's lm3s6965evb
# with UART0 (the host link) and UART1 (CAN frames as SLCAN text) on new pseudo-terminals,
# bridges UART1 to the python-can bus URL with `pdcp-studio can-bridge`, and prints
# "host link on /dev/pts/N" on stdout once the host link answers a HELLO — the way
# `pdcp-studio arbitrator --host-serial pty` does. Runs until interrupted; then stops QEMU and
# the bridge. FILE is the arbitrator's non-volatile memory (PDCP Studio's memory-file layout,
# through semihosting; created if missing); without it a temporary file is used and removed.
# PDCP_STUDIO names the command that runs PDCP Studio (default: pdcp-studio if on PATH, else
# "python3 -m pdcp_studio"); PDCP_FW_LOG a file for QEMU's output and the firmware's log lines.
set -u
here=$(cd "$(dirname "$0")" && pwd)
bus=""
memory=""
while [ $# -gt 0 ]; do
    case "$1" in
        --bus) bus="${2:-}"; shift 2 ;;
        --memory) memory="${2:-}"; shift 2 ;;
        -h|--help) awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"; exit 0 ;;
        *) echo "run-qemu.sh: unknown argument $1 (usage: run-qemu.sh --bus URL [--memory FILE])" >&2; exit 2 ;;
    esac
done
[ -n "$bus" ] || { echo "run-qemu.sh: --bus URL is required (a can: bus URL)" >&2; exit 2; }
case "$bus" in can:*) ;; *) echo "run-qemu.sh: --bus $bus: the firmware's CAN side joins a can: bus" >&2; exit 2 ;; esac
for tool in qemu-system-arm arm-none-eabi-gcc make; do
    command -v "$tool" >/dev/null 2>&1 || { echo "run-qemu.sh: $tool is missing (apt-get install gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm make)" >&2; exit 1; }
done
if [ -z "${PDCP_STUDIO:-}" ]; then
    if command -v pdcp-studio >/dev/null 2>&1; then PDCP_STUDIO=pdcp-studio; else PDCP_STUDIO="python3 -m pdcp_studio"; fi
fi
python=$(echo "$PDCP_STUDIO" | awk '{ if ($2 == "-m") print $1; }')
if [ -z "$python" ]; then
    python=$(head -1 "$(command -v "$PDCP_STUDIO")" 2>/dev/null | sed -n 's/^#! *//p')
    [ -n "$python" ] || python=python3
fi

# One build at a time in build/ (two at once, e.g. two emulators started together on a fresh
# checkout, wrote a broken ELF): flock(1), from util-linux, where it is installed.
mkdir -p "$here/build"
if command -v flock >/dev/null 2>&1; then
    flock "$here/build/.lock" make -s -C "$here" arm >&2
else
    make -s -C "$here" arm >&2
fi || { echo "run-qemu.sh: the firmware did not build" >&2; exit 1; }

work=$(mktemp -d "${TMPDIR:-/tmp}/pdcp-fw.XXXXXX")
if [ -z "$memory" ]; then memory="$work/memory.bin"; fi
case "$memory" in *" "*) echo "run-qemu.sh: --memory $memory: a path without spaces, please (semihosting arguments)" >&2; exit 2 ;; esac
case "$memory" in /*) ;; *) memory="$(pwd)/$memory" ;; esac
qemu_pid=""
bridge_pid=""
cleanup() {
    [ -n "$bridge_pid" ] && kill "$bridge_pid" 2>/dev/null
    [ -n "$qemu_pid" ] && kill "$qemu_pid" 2>/dev/null
    [ -n "$bridge_pid" ] && wait "$bridge_pid" 2>/dev/null
    [ -n "$qemu_pid" ] && wait "$qemu_pid" 2>/dev/null
    rm -rf "$work"
}
trap 'cleanup; exit 0' INT TERM
trap cleanup EXIT

qemu-system-arm -M lm3s6965evb -display none -monitor none \
    -chardev pty,id=host -chardev pty,id=can -serial chardev:host -serial chardev:can \
    -semihosting-config enable=on,target=native,arg=pdcp-fw,arg="$memory" \
    -kernel "$here/build/arm/pdcp-fw.elf" >"${PDCP_FW_LOG:-$work/qemu.log}" 2>&1 &
qemu_pid=$!

host=""; can=""
tries=0
while [ $tries -lt 100 ]; do
    host=$(sed -n 's/.*redirected to \(\/dev\/[^ ]*\) (label host).*/\1/p' "${PDCP_FW_LOG:-$work/qemu.log}")
    can=$(sed -n 's/.*redirected to \(\/dev\/[^ ]*\) (label can).*/\1/p' "${PDCP_FW_LOG:-$work/qemu.log}")
    [ -n "$host" ] && [ -n "$can" ] && break
    kill -0 "$qemu_pid" 2>/dev/null || break
    sleep 0.05; tries=$((tries + 1))
done
if [ -z "$host" ] || [ -z "$can" ]; then
    echo "run-qemu.sh: QEMU did not start:" >&2; cat "${PDCP_FW_LOG:-$work/qemu.log}" >&2; exit 1
fi

$PDCP_STUDIO can-bridge --serial "$can" --bus "$bus" 2>"$work/bridge.log" &
bridge_pid=$!

# The host link answers a HELLO (RESET, HELLO v2; its reply is acknowledged).
if ! "$python" - "$host" <<'EOF'
import sys, time
import serial
from pdcp_studio.protocol.hostlink import Frame, FrameReader, Kind
port = serial.Serial(sys.argv[1], 115200, timeout=0.05)
reader = FrameReader()
deadline = time.monotonic() + 20
ok = False
while time.monotonic() < deadline and not ok:
    port.write(Frame(Kind.RESET, 0).encode() + Frame(Kind.DATA, 0, b"\x01\x02\xff\xff").encode())
    until = time.monotonic() + 0.5
    while time.monotonic() < until and not ok:
        for item in reader.feed(port.read(256)):
            if isinstance(item, Frame) and item.kind is Kind.DATA and item.payload[:2] == b"\x81\x00":
                port.write(Frame(Kind.ACK, item.seq).encode())
                ok = True
port.close()
sys.exit(0 if ok else 1)
EOF
then
    echo "run-qemu.sh: the firmware's host link did not answer on $host" >&2
    cat "${PDCP_FW_LOG:-$work/qemu.log}" "$work/bridge.log" >&2
    exit 1
fi
echo "host link on $host"
kill -0 "$bridge_pid" 2>/dev/null || { echo "run-qemu.sh: the CAN bridge stopped:" >&2; cat "$work/bridge.log" >&2; exit 1; }
wait "$qemu_pid"
status=$?
qemu_pid=""
exit $status
