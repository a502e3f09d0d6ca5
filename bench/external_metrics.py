#!/usr/bin/env python3
"""Times scikit-image's SSIM and PSNR on the benchmark's 1080p pair, the way aalab_bench
times its own metrics (one untimed warm-up call, then N timed calls, wall clock), and prints
one JSON object: {"ssim": {"samples_ms": [...], "value": v}, "psnr": {...}} or
{"error": "..."} when scikit-image is missing.

Usage: external_metrics.py A.f32 B.f32 WIDTH HEIGHT REPEATS
A.f32 / B.f32: raw little-endian float32, H x W x 3, row-major (written by aalab_bench).
Inputs are converted to float64 first (not timed), as METRICS.md prescribes for
cross-checks: scikit-image then filters in float64, as aalab does.
"""
import json
import sys
import time


def main():
    a_path, b_path, w, h, reps = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
    try:
        import numpy as np
        from skimage.metrics import peak_signal_noise_ratio, structural_similarity
        import skimage
    except Exception as e:  # noqa: BLE001 - report any import problem
        print(json.dumps({"error": "scikit-image not available: %s" % e}))
        return 0
    a = np.fromfile(a_path, dtype="<f4").reshape(h, w, 3).astype(np.float64)
    b = np.fromfile(b_path, dtype="<f4").reshape(h, w, 3).astype(np.float64)

    def ssim():
        return structural_similarity(a, b, channel_axis=2, gaussian_weights=True, sigma=1.5,
                                     use_sample_covariance=False, data_range=1.0)

    def psnr():
        return peak_signal_noise_ratio(a, b, data_range=1.0)

    out = {"skimage_version": skimage.__version__, "numpy_version": np.__version__}
    for name, fn in (("ssim", ssim), ("psnr", psnr)):
        value = fn()  # warm-up
        samples = []
        for _ in range(reps):
            t0 = time.perf_counter()
            fn()
            samples.append((time.perf_counter() - t0) * 1000.0)
        out[name] = {"samples_ms": samples, "value": float(value)}
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
