#!/usr/bin/env bash
# Where the trace kernel's time goes on lavapipe, down to its machine code.
#
#   bench/profile-kernel.sh [--out DIR] -- COMMAND...
#   bench/profile-kernel.sh -- build/vkray render scenes/whitted.sdl --size 1920x1080 -o /tmp/w.png
#   bench/profile-kernel.sh -- build/vkray_bench --scenes castle --no-cpu --no-embree --no-fma --no-all
#
# llvmpipe JIT-compiles the shader into anonymous memory, which perf samples
# but cannot name. This runs COMMAND (vkray or vkray_bench) under perf (a
# cpu-clock sample every 200 us on every thread) and gdb, stops it when its
# first GpuTracer goes (the JIT code is still mapped then), copies every
# executable anonymous mapping to DIR, and hands both to
# bench/profile_kernel.py, which prints the process's time by part (the
# kernel code, the driver, the host, the OS), the kernel's loops with their
# shares, the share of llvmpipe's per-lane loops (each word a shader stores
# is one, docs/lavapipe.md) and the hottest spots, and writes the annotated
# disassembly to DIR/kernel.txt. Needs perf, gdb, objdump and python3
# (Debian: apt-get install linux-perf gdb binutils python3); perf must be
# allowed to sample (kernel.perf_event_paranoid <= 2, or root).
set -euo pipefail

out=profile-kernel
if [ "${1:-}" = "--out" ]; then
  out=$2
  shift 2
fi
if [ "${1:-}" != "--" ] || [ $# -lt 2 ]; then
  sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
shift
for tool in perf gdb objdump python3; do
  if ! command -v "$tool" >/dev/null; then
    echo "profile-kernel: $tool is not installed (apt-get install linux-perf gdb binutils python3)" >&2
    exit 1
  fi
done
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
out=$(cd "$out" && pwd)
rm -f "$out"/region_*.bin "$out"/regions.txt

# gdb's part: at the breakpoint, copy each anonymous executable mapping.
cat > "$out/dump.py" <<'EOF'
import gdb, os
out = os.environ["PROFILE_KERNEL_OUT"]
inferior = gdb.selected_inferior()
with open(out + "/regions.txt", "w") as regions:
    for line in open("/proc/%d/maps" % inferior.pid):
        fields = line.split()
        if "x" not in fields[1] or (len(fields) >= 6 and fields[5] != ""):
            continue
        lo, hi = [int(x, 16) for x in fields[0].split("-")]
        try:
            code = bytes(inferior.read_memory(lo, hi - lo))
        except gdb.MemoryError:
            continue
        path = "%s/region_%x.bin" % (out, lo)
        open(path, "wb").write(code)
        regions.write("%x %x %s\n" % (lo, hi, path))
EOF

PROFILE_KERNEL_OUT="$out" perf record -q -e cpu-clock -F 5000 -o "$out/perf.data" -- \
  gdb -q -batch -ex 'set pagination off' -ex 'set breakpoint pending on' \
  -ex 'break vkray::gpu::GpuTracer::~GpuTracer' -ex run -ex "source $out/dump.py" -ex kill \
  --args "$@" > "$out/command.log" 2>&1 || true
if [ ! -s "$out/regions.txt" ]; then
  echo "profile-kernel: no JIT code was mapped when the command's first GpuTracer went (did it render on the GPU?); its output is in $out/command.log" >&2
  exit 1
fi
perf script -i "$out/perf.data" -F comm,ip,dso > "$out/samples.txt" 2>/dev/null
python3 "$here/profile_kernel.py" "$out"
