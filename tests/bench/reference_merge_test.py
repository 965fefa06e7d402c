"""bench/make_mitsuba_reference.py --extend: a reference made in two sittings is the one made in
one. Pass means of a known distribution (per pixel a mean and a spread), split into two sittings
of unequal length: the combined mean equals the mean over all passes, and the combined variance of
the mean matches the true one (the pass spread squared over all passes) on average over 16384
pixels, within the estimate's own statistical spread. Plain Python: no numpy needed.

  tests/bench/reference_merge_test.py REPO
"""
import os
import random
import sys

sys.path.insert(0, os.path.join(sys.argv[1] if len(sys.argv) > 1 else ".", "bench"))
from make_mitsuba_reference import combine, mean_and_variance  # noqa: E402

rng = random.Random(7)
pixels, passes_a, passes_b, pass_spp = 16384, 12, 36, 256


def sitting(values):
    return mean_and_variance(sum(values), sum(v * v for v in values), len(values))


failures = []
ratio_sum = err_sum = err_b_sum = 0.0
worst_mean = 0.0
for _ in range(pixels):
    truth, spread = rng.uniform(0.1, 2.0), rng.uniform(0.05, 0.5)
    x = [rng.gauss(truth, spread) for _ in range(passes_a + passes_b)]
    mean_a, var_a = sitting(x[:passes_a])
    mean_b, var_b = sitting(x[passes_a:])
    mean, var = combine(mean_a, var_a, passes_a * pass_spp, mean_b, var_b, passes_b * pass_spp)
    worst_mean = max(worst_mean, abs(mean - sum(x) / len(x)))
    ratio_sum += var / (spread * spread / len(x))
    err_sum += (mean - truth) ** 2
    err_b_sum += (mean_b - truth) ** 2
ratio = ratio_sum / pixels
if worst_mean > 1e-12:
    failures.append(f"the combined mean differs from the mean over all passes by up to {worst_mean:.3g}")
if abs(ratio - 1.0) > 0.03:  # its own spread over 16384 pixels: about 0.6%
    failures.append(f"the combined variance of the mean is {ratio:.4f}x the true one")
if not err_sum < err_b_sum:
    failures.append(f"combining did not help: squared error {err_sum:.3g} against {err_b_sum:.3g} for the longer sitting")
for f in failures:
    print("FAIL:", f)
print(f"combined variance / true: {ratio:.4f}; squared error {err_sum / pixels:.3g} "
      f"(the longer sitting alone {err_b_sum / pixels:.3g})")
sys.exit(1 if failures else 0)
