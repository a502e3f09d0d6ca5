#!/usr/bin/env python3
"""Independent reference values for tests/metrics/crosscheck_test.cpp (not run by CI).

Builds the same deterministic image pairs as the C++ test (integer-only generator, so both
sides see identical pixels) and prints
  - SSIM from scikit-image (0.19.3 checked): structural_similarity(ref, test, channel_axis=2,
    gaussian_weights=True, sigma=1.5, use_sample_covariance=False, data_range=1) on float64
    arrays (float32 arrays make scikit-image filter in float32, ~1e-7 off);
  - LDR-FLIP from a direct numpy/scipy transcription of NVIDIA's python reference
    (NVlabs/flip python/flip.py, compute_ldrflip): full 2-D kernels (not separable),
    correlation with replicated borders (cv.BORDER_REPLICATE == scipy mode 'nearest'), all in
    float64, pooled as mean, value-weighted median (NVIDIA pooling.getPercentile(0.5, True))
    and max.
Needs numpy, scipy, scikit-image (Debian: python3-skimage). Run:
  /usr/bin/python3 tests/metrics/crosscheck_reference.py
"""
import numpy as np
from scipy import ndimage
from skimage.metrics import structural_similarity

M32 = 0xFFFFFFFF


def hash32(x):
    """lowbias32 integer hash (same as the C++ test)."""
    x &= M32
    x ^= x >> 16
    x = (x * 0x7FEB352D) & M32
    x ^= x >> 15
    x = (x * 0x846CA68B) & M32
    x ^= x >> 16
    return x


def make_pair(w, h, seed):
    """8-bit codes: a gradient with a slanted edge and texture, and a blurred noisy copy."""
    ref = np.zeros((h, w, 3), dtype=np.int64)
    for y in range(h):
        for x in range(w):
            for c in range(3):
                v = 40 + (x * 3 + y * 2 + c * 20) % 160
                if 5 * x + 3 * y > 2 * w + h:
                    v += 60
                v += hash32(seed * 1000003 + x + 1000 * y + 7919 * c) % 21 - 10
                ref[y, x, c] = min(max(v, 0), 255)
    test = np.zeros_like(ref)
    for y in range(h):
        for x in range(w):
            for c in range(3):
                s = ref[y, max(x - 1, 0), c] + ref[y, x, c] + ref[y, min(x + 1, w - 1), c]
                v = (s + 1) // 3 + hash32(seed * 1000003 + 12345 + x + 1000 * y + 7919 * c) % 9 - 4
                test[y, x, c] = min(max(v, 0), 255)
    # The C++ images are float32 (k / 255 rounded to float); use exactly those values.
    f = lambda codes: (codes.astype(np.float64) / 255.0).astype(np.float32).astype(np.float64)
    return f(ref), f(test)


# ---- LDR-FLIP, after NVIDIA python/flip.py (float64 here) ----
WHITE = np.array([0.950428545, 1.0, 1.088900371])
RGB2XYZ = np.array([[10135552 / 24577794, 8788810 / 24577794, 4435075 / 24577794],
                    [2613072 / 12288897, 8788810 / 12288897, 887015 / 12288897],
                    [1425312 / 73733382, 8788810 / 73733382, 70074185 / 73733382]])
XYZ2RGB = np.linalg.inv(RGB2XYZ)


def srgb2lin(v):
    return np.where(v > 0.04045, ((v + 0.055) / 1.055) ** 2.4, v / 12.92)


def xyz2ycxcz(xyz):
    n = xyz / WHITE
    return np.stack([116 * n[..., 1] - 16, 500 * (n[..., 0] - n[..., 1]), 200 * (n[..., 1] - n[..., 2])], -1)


def ycxcz2xyz(o):
    y = (o[..., 0] + 16) / 116
    return np.stack([y + o[..., 1] / 500, y, y - o[..., 2] / 200], -1) * WHITE


def xyz2lab(xyz):
    n = xyz / WHITE
    d = 6 / 29
    f = np.where(n > d ** 3, np.cbrt(n), n / (3 * d * d) + 4 / 29)
    return np.stack([116 * f[..., 1] - 16, 500 * (f[..., 0] - f[..., 1]), 200 * (f[..., 1] - f[..., 2])], -1)


def hunt(lab):
    return np.stack([lab[..., 0], 0.01 * lab[..., 0] * lab[..., 1], 0.01 * lab[..., 0] * lab[..., 2]], -1)


def hyab(a, b):
    d = a - b
    return np.abs(d[..., 0]) + np.sqrt(d[..., 1] ** 2 + d[..., 2] ** 2)


def spatial_filter(ppd, a1, b1, a2, b2):
    r = int(np.ceil(3 * np.sqrt(0.04 / (2 * np.pi ** 2)) * ppd))
    x, y = np.meshgrid(range(-r, r + 1), range(-r, r + 1))
    z = (x / ppd) ** 2 + (y / ppd) ** 2
    s = a1 * np.sqrt(np.pi / b1) * np.exp(-np.pi ** 2 * z / b1) + a2 * np.sqrt(np.pi / b2) * np.exp(-np.pi ** 2 * z / b2)
    return s / s.sum()


def feature_kernel(ppd, kind):
    sd = 0.5 * 0.082 * ppd
    r = int(np.ceil(3 * sd))
    x, y = np.meshgrid(range(-r, r + 1), range(-r, r + 1))
    g = np.exp(-(x ** 2 + y ** 2) / (2 * sd * sd))
    k = -x * g if kind == 'edge' else (x ** 2 / (sd * sd) - 1) * g
    neg, pos = -k[k < 0].sum(), k[k > 0].sum()
    return np.where(k < 0, k / neg, k / pos)


def corr(img, k):
    return ndimage.correlate(img, k, mode='nearest')


def ldrflip(ref, test, ppd):
    cmax = hyab(hunt(xyz2lab(RGB2XYZ @ np.array([0.0, 1.0, 0.0]))),
                hunt(xyz2lab(RGB2XYZ @ np.array([0.0, 0.0, 1.0])))) ** 0.7
    kernels = [spatial_filter(ppd, 1, 0.0047, 0, 1e-5), spatial_filter(ppd, 1, 0.0053, 0, 1e-5),
               spatial_filter(ppd, 34.1, 0.04, 13.5, 0.025)]
    ke, kp = feature_kernel(ppd, 'edge'), feature_kernel(ppd, 'point')
    labs, feats = [], []
    for img in (ref, test):
        o = xyz2ycxcz(srgb2lin(img) @ RGB2XYZ.T)
        f = np.stack([corr(o[..., c], kernels[c]) for c in range(3)], -1)
        rgb = np.clip(ycxcz2xyz(f) @ XYZ2RGB.T, 0, 1)
        labs.append(hunt(xyz2lab(rgb @ RGB2XYZ.T)))
        yn = (o[..., 0] + 16) / 116
        edge = np.hypot(corr(yn, ke), corr(yn, ke.T))
        point = np.hypot(corr(yn, kp), corr(yn, kp.T))
        feats.append((edge, point))
    x = hyab(labs[0], labs[1]) ** 0.7
    pcc = 0.4 * cmax
    dec = np.where(x < pcc, x * (0.95 / pcc), 0.95 + (x - pcc) / (cmax - pcc) * 0.05)
    dfe = np.maximum(np.abs(feats[0][0] - feats[1][0]), np.abs(feats[0][1] - feats[1][1]))
    def_ = np.sqrt(dfe / np.sqrt(2))
    return dec ** (1 - def_)


def weighted_median(v):
    s = np.sort(v.ravel())
    total = s.sum()
    if total == 0:
        return 0.0
    return float(s[np.argmax(np.cumsum(s) > 0.5 * total)])


if __name__ == '__main__':
    for (w, h, seed) in [(48, 40, 1), (33, 21, 2)]:
        ref, test = make_pair(w, h, seed)
        ssim = structural_similarity(ref, test, channel_axis=2, gaussian_weights=True, sigma=1.5,
                                     use_sample_covariance=False, data_range=1.0)
        for ppd in (67.0, 20.0):
            m = ldrflip(ref, test, ppd)
            print(f"{w}x{h} seed {seed} ppd {ppd}: ssim {ssim!r} flip_mean {float(m.mean())!r} "
                  f"flip_wmedian {weighted_median(m)!r} flip_max {float(m.max())!r} "
                  f"flip(3,4) {float(m[4, 3])!r}")
