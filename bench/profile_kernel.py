#!/usr/bin/env python3
"""The analysis half of bench/profile-kernel.sh: perf's samples of a vkray
process against the machine code llvmpipe JIT-compiled for it.

Reads DIR/samples.txt (perf script -F comm,ip,dso) and DIR/regions.txt (the
executable anonymous mappings gdb copied), prints where the process's time
went and, in the kernel (the compiled shader with the most samples), its
loops, its per-lane loops and its hottest spots; writes DIR/kernel.txt, the
kernel's disassembly with each instruction's samples.
"""
import collections
import re
import subprocess
import sys

TOOL_COMMANDS = ("gdb", "gdb worker")  # the profiler's own threads, not the process's


def read_samples(path):
    """(command, address, dso) of each sample."""
    samples = []
    line_form = re.compile(r"^\s*(.*?)\s+([0-9a-f]+)\s+\((.*)\)\s*$")
    for line in open(path):
        m = line_form.match(line)
        if m and m.group(1) not in TOOL_COMMANDS:
            samples.append((m.group(1), int(m.group(2), 16), m.group(3)))
    return samples


def part_of(dso):
    if "perf-" in dso and dso.endswith(".map") or dso.startswith("[JIT]"):
        return "kernel (JIT code)"
    if "kernel.kallsyms" in dso:
        return "operating system"
    if "lvp" in dso or "LLVM" in dso or "gallium" in dso:
        return "driver (lavapipe, LLVM)"
    if dso.endswith("vkray") or dso.endswith("vkray_bench"):
        return "host (vkray)"
    return "libraries"


def disassemble(path, base):
    """[(address, text)] of the code at `path`, loaded at `base`."""
    listing = subprocess.run(
        ["objdump", "-D", "-b", "binary", "-m", "i386:x86-64", "--adjust-vma=0x%x" % base, path],
        check=True, capture_output=True, text=True).stdout
    code = []
    for line in listing.splitlines():
        m = re.match(r"\s*([0-9a-f]+):\t(?:[0-9a-f]{2} )+\s*\t?(.*)", line)
        if m and m.group(2):
            code.append((int(m.group(1), 16), m.group(2).strip()))
    return code


def main(out):
    samples = read_samples(out + "/samples.txt")
    if not samples:
        sys.exit("profile-kernel: perf recorded no samples of the command")
    parts = collections.Counter(part_of(dso) for _, _, dso in samples)
    total = len(samples)
    print("samples: %d of the process (every 200 us of each thread)" % total)
    for part, count in parts.most_common():
        print("  %-26s %5.1f %%" % (part, 100.0 * count / total))

    # The kernel: the copied region, and within it the function (the code
    # between two prologues), with the most samples.
    regions = [(int(lo, 16), int(hi, 16), path)
               for lo, hi, path in (l.split() for l in open(out + "/regions.txt"))]
    jit = collections.Counter(ip for _, ip, dso in samples if part_of(dso) == "kernel (JIT code)")
    lo, hi, path = max(regions, key=lambda r: sum(c for ip, c in jit.items() if r[0] <= ip < r[1]))
    code = disassemble(path, lo)
    starts = [a for i, (a, text) in enumerate(code)
              if text.startswith("push") and "%rbp" in text and i + 1 < len(code)
              and code[i + 1][1].startswith("mov") and "%rsp,%rbp" in code[i + 1][1]]
    bounds = list(zip(starts, starts[1:] + [hi]))
    begin, end = max(bounds, key=lambda b: sum(c for ip, c in jit.items() if b[0] <= ip < b[1]))
    code = [(a, t) for a, t in code if begin <= a < end]
    counts = [jit.get(a, 0) for a, _ in code]
    kernel = sum(counts)
    if kernel == 0:
        sys.exit("profile-kernel: no sample fell in the copied code")
    print("\nthe kernel: %d bytes of code at %x, %d samples (%.1f %% of the process)"
          % (end - begin, begin, kernel, 100.0 * kernel / total))

    def share(first, last):
        return 100.0 * sum(c for (a, _), c in zip(code, counts) if first <= a <= last) / kernel

    loops = []
    for (a, text), c in zip(code, counts):
        m = re.match(r"j\w+\s+0x([0-9a-f]+)", text)
        if m and int(m.group(1), 16) < a:
            loops.append((int(m.group(1), 16), a))
    # llvmpipe's own per-lane loops: a few dozen bytes, eight turns, a lane each.
    small = [(f, l) for f, l in loops if l - f < 0x80]
    stores = [(f, l) for f, l in small
              if any(re.match(r"mov\w*\s+%\w+,\((%r\w+)\)$", t) for a, t in code if f <= a <= l)]
    covered = set()
    for f, l in stores:
        covered.update(a for a, _ in code if f <= a <= l + 8)
    print("per-lane store loops (each word a shader stores): %d, %.1f %% of the kernel"
          % (len({l for _, l in stores}),
             100.0 * sum(c for (a, _), c in zip(code, counts) if a in covered) / kernel))
    print("\nits loops (the shader's; offsets from its start), by share:")
    for f, l in sorted({(f, l) for f, l in loops if l - f >= 0x80}, key=lambda x: -share(*x)):
        if share(f, l) >= 0.5:
            print("  %6x-%6x  %6d bytes  %5.1f %%" % (f - begin, l - begin, l - f, share(f, l)))
    blocks = collections.Counter()
    for (a, _), c in zip(code, counts):
        blocks[(a - begin) // 256] += c
    print("\nhottest 256-byte spans:")
    for block, c in blocks.most_common(8):
        print("  %6x  %5.1f %%" % (block * 256, 100.0 * c / kernel))
    with open(out + "/kernel.txt", "w") as listing:
        for (a, text), c in zip(code, counts):
            listing.write("%6d %5.2f%% %6x  %s\n" % (c, 100.0 * c / kernel, a - begin, text))
    print("\nannotated disassembly: %s/kernel.txt" % out)


if __name__ == "__main__":
    main(sys.argv[1])
