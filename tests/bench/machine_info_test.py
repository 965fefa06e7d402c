"""bench/machine_info.py names the CPU as the benchmarks' figures must: every model name gets its
family and model numbers, an AMD one its core generation too (a cloud machine's bare "AMD EPYC" is
Zen 2 to Zen 5, which run lavapipe differently), only the first processor's fields count, and the
ISA is the widest the flags list.

  tests/bench/machine_info_test.py REPO
"""
import os
import sys

sys.path.insert(0, os.path.join(sys.argv[1] if len(sys.argv) > 1 else ".", "bench"))
from machine_info import amd_generation, describe  # noqa: E402


def cpuinfo(vendor, family, model, name, flags):
    # Two processors, as /proc/cpuinfo lists them: only the first is read.
    one = (f"processor\t: 0\nvendor_id\t: {vendor}\ncpu family\t: {family}\nmodel\t\t: {model}\n"
           f"model name\t: {name}\nflags\t\t: {flags}\n")
    return one + "\n" + one.replace("processor\t: 0", "processor\t: 1").replace(name, "second CPU") + "\n"


failures = []


def check(what, got, want):
    if got != want:
        failures.append(f"{what}: got {got!r}, want {want!r}")


check("Zen 5 EPYC (family 26)", describe(cpuinfo("AuthenticAMD", 26, 2, "AMD EPYC", "fpu avx2 avx512f"), 2),
      "2 cores, AMD EPYC (family 26, model 2, Zen 5), AVX-512")
check("Zen 4 Genoa (family 25, model 17)", describe(cpuinfo("AuthenticAMD", 25, 17, "AMD EPYC", "avx2 avx512f"), 2),
      "2 cores, AMD EPYC (family 25, model 17, Zen 4), AVX-512")
check("Zen 3 Milan (family 25, model 1)", describe(cpuinfo("AuthenticAMD", 25, 1, "AMD EPYC 7763", "avx2"), 4),
      "4 cores, AMD EPYC 7763 (family 25, model 1, Zen 3), AVX2")
check("Intel: family and model, no generation",
      describe(cpuinfo("GenuineIntel", 6, 143, "Intel(R) Xeon(R) Platinum 8481C CPU @ 2.70GHz", "sse4_2 avx2 avx512f"), 2),
      "2 cores, Intel(R) Xeon(R) Platinum 8481C CPU @ 2.70GHz (family 6, model 143), AVX-512")
check("no vector extensions", describe(cpuinfo("AuthenticAMD", 23, 49, "AMD EPYC 7B12", "fpu"), 1),
      "1 cores, AMD EPYC 7B12 (family 23, model 49, Zen 2), ?")
for family, model, want in ((0x17, 0x01, "Zen or Zen+"), (0x17, 0x31, "Zen 2"), (0x19, 0x61, "Zen 4"),
                            (0x19, 0x21, "Zen 3"), (0x19, 0xA0, "Zen 4"), (0x1A, 0x44, "Zen 5"), (0x15, 0x02, None)):
    check(f"amd_generation({family:#x}, {model:#x})", amd_generation(family, model), want)

for f in failures:
    print("FAIL", f)
print(f"{'FAILED' if failures else 'passed'}: machine_info")
sys.exit(1 if failures else 0)
