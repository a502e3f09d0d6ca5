#!/usr/bin/env python3
"""Fits the texture unit's bilinear arithmetic to `aalab_gpu --probe-dump DIR` data.

Usage: scripts/fit_texture_rule.py DIR   (needs python3-numpy; not part of the build or CI)

Tests each hypothesis of docs/gpu.md "The CPU mode that predicts the GPU's bits" against the
raw samples and prints how many samples each one misses; the rule core/sampler.h
implements (--sampler gpu-texture) is the one that misses none. aalab_gpu checks the same
rule on the device itself (CheckTextureRule, every run).
"""
import sys

import numpy as np


def f16(q):
    """The 16-bit filtered value q as the float the unit returns: q/65535 correctly rounded."""
    return (np.asarray(q, np.float64) / 65535).astype(np.float32)


def corner_weights(kx, ky, rule):
    p = kx * ky
    d = {"round-half-up": (p + 128) // 256, "truncate": p // 256,
         "round-half-even": np.where(p % 256 == 128, p // 256 + ((p // 256) & 1), (p + 128) // 256)}[rule]
    return 256 - kx - ky + d, kx - d, ky - d, d


def main(d):
    raw = open(d + "/pairs.bin", "rb").read()
    nk = np.frombuffer(raw[:4], np.int32)[0]
    ks = np.frombuffer(raw[4:4 + 4 * nk], np.int32).astype(np.int64)
    out = np.frombuffer(raw[4 + 4 * nk:], np.float32).reshape(nk, 256, 256)
    a = np.arange(256, dtype=np.int64)[None, :, None]
    b = np.arange(256, dtype=np.int64)[None, None, :]
    k = ks[:, None, None]
    s = ((256 - k) * a + k * b) * 257  # 16-bit units times 256
    exact = s / 256.0 / 65535.0
    print("pairs (%d samples at 8-bit weights %s):" % (out.size, list(ks)))
    print("  float32 of the exact value      : %d differ" % (exact.astype(np.float32) != out).sum())
    for name, q in [("16 bits, ties upwards", (s + 128) // 256), ("16 bits, truncated", s // 256)]:
        print("  %-32s: %d differ" % (name, (f16(q) != out).sum()))

    tex = np.frombuffer(open(d + "/quad8_tex.bin", "rb").read(), np.uint8).reshape(512, 1024, 4).astype(np.int64)
    rec = np.frombuffer(open(d + "/quad8.bin", "rb").read(), dtype=np.dtype([("p", "<i2", 4), ("o", "<f4", 4)]))
    p = rec["p"].astype(np.int64)
    x, y, kx, ky = p[:, 0], p[:, 1], p[:, 2], p[:, 3]
    A, B, C, D = tex[y, x], tex[y, x + 1], tex[y + 1, x], tex[y + 1, x + 1]
    print("RGBA8 2-D fetches (%d channel samples):" % rec["o"].size)
    prod = ((256 - kx) * (256 - ky))[:, None] * A + (kx * (256 - ky))[:, None] * B + \
        ((256 - kx) * ky)[:, None] * C + (kx * ky)[:, None] * D
    print("  product weights wx*wy, 16 bits  : %d differ" % (f16((prod * 257 + 32768) // 65536) != rec["o"]).sum())
    for rule in ("round-half-up", "truncate", "round-half-even"):
        wa, wb, wc, wd = corner_weights(kx, ky, rule)
        ssum = wa[:, None] * A + wb[:, None] * B + wc[:, None] * C + wd[:, None] * D
        print("  8-bit corner weight, %-11s: %d differ" % (rule, (f16((257 * ssum + 128) // 256) != rec["o"]).sum()))

    raw = open(d + "/coord.bin", "rb").read()
    pos, total, miss_exact, miss_rule = 0, 0, 0, 0
    while pos < len(raw):
        size, axis, norm, n = np.frombuffer(raw[pos:pos + 16], np.int32)
        pos += 16
        c = np.frombuffer(raw[pos:pos + 4 * n], np.float32).astype(np.float64)
        pos += 4 * n
        q = np.frombuffer(raw[pos:pos + 2 * n], np.uint16).astype(np.int64)
        pos += 2 * n

        def predict(u):
            t = np.floor((u - 0.5) * 256 + 0.5).astype(np.int64)
            x0, kk = t // 256, t % 256
            tx = lambda i: np.where(np.clip(i, 0, size - 1) & 1, 255, 0)
            return (257 * ((256 - kk) * tx(x0) + kk * tx(x0 + 1)) + 128) // 256

        u_exact = c * size if norm else c
        u_rule = np.floor(c * 2 ** 21) * size / 2 ** 21 if norm else c
        total += n
        miss_exact += (predict(u_exact) != q).sum()
        miss_rule += (predict(u_rule) != q).sum()
    print("coordinates (%d samples, sizes 16..5120, both axes):" % total)
    print("  exact s*W, 1/256 ties upwards   : %d differ" % miss_exact)
    print("  s truncated to 2^-21, then *W   : %d differ" % miss_rule)

    tex = np.frombuffer(open(d + "/quadf_tex.bin", "rb").read(), np.float32).reshape(256, 256, 4).astype(np.float64)
    rec = np.frombuffer(open(d + "/quadf.bin", "rb").read(), dtype=np.dtype([("p", "<i2", 4), ("o", "<f4", 4)]))
    p = rec["p"].astype(np.int64)
    x, y, kx, ky = p[:, 0], p[:, 1], p[:, 2], p[:, 3]
    wa, wb, wc, wd = corner_weights(kx, ky, "round-half-up")
    ssum = (wa[:, None] * tex[y, x] + wb[:, None] * tex[y, x + 1] + wc[:, None] * tex[y + 1, x] +
            wd[:, None] * tex[y + 1, x + 1]) / 256
    m, e = np.frexp(ssum)
    ties_up = np.ldexp(np.floor(np.ldexp(m, 24) + 0.5), e - 24).astype(np.float32)
    print("RGBA32F 2-D fetches (%d channel samples):" % rec["o"].size)
    print("  exact sum, nearest-even float   : %d differ" % (ssum.astype(np.float32) != rec["o"]).sum())
    print("  exact sum, ties upwards         : %d differ" % (ties_up != rec["o"]).sum())


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
