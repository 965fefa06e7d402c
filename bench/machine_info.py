"""The machine a benchmark ran on, named as its figures should name it: cores, the CPU's model
name, its family and model numbers with the core generation where the name leaves it out, and the
widest vector ISA. Cloud machines often report only "AMD EPYC", which covers Zen 2 to Zen 5, and
lavapipe's speed changes between those (bench/RESULTS.md: AVX2 code 1.6-2x slower than AVX-512 on
Zen 4, level on Zen 5).
"""
import os


def amd_generation(family, model):
    """AMD's core generation from the cpuid family and model (AMD's processor programming
    references): family 17h is Zen to Zen 2, 19h Zen 3 or Zen 4 by model range, 1Ah Zen 5."""
    if family == 0x17:
        return "Zen 2" if model >= 0x30 else "Zen or Zen+"
    if family == 0x19:
        zen4 = 0x10 <= model <= 0x1F or 0x60 <= model <= 0x7F or 0xA0 <= model <= 0xAF
        return "Zen 4" if zen4 else "Zen 3"
    if family == 0x1A:
        return "Zen 5"
    return None


def describe(cpuinfo_text, cores):
    """One line from the text of /proc/cpuinfo (its first processor's fields)."""
    fields = {}
    for line in cpuinfo_text.splitlines():
        if not line.strip():
            if fields:
                break
            continue
        key, _, value = line.partition(":")
        fields.setdefault(key.strip(), value.strip())
    name = fields.get("model name", "?")
    flags = set(fields.get("flags", "").split())
    cpu = name
    if fields.get("cpu family", "").isdigit() and fields.get("model", "").isdigit():
        family, model = int(fields["cpu family"]), int(fields["model"])
        generation = amd_generation(family, model) if fields.get("vendor_id") == "AuthenticAMD" else None
        cpu = f"{name} (family {family}, model {model}{', ' + generation if generation else ''})"
    isa = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else "SSE4" if "sse4_2" in flags else "?"
    return f"{cores} cores, {cpu}, {isa}"


def machine():
    """This machine, counting the cores this process may run on (as nproc does)."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    with open("/proc/cpuinfo") as f:
        return describe(f.read(), cores)


if __name__ == "__main__":
    print(machine())
