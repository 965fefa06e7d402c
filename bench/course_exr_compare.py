#!/usr/bin/env python3
"""Compares pt's renders of course scenes with the course's official OpenEXR outputs in linear
radiance: the mean relative difference of 16x16-pixel block means (noise averages out; what
remains is bias), and the ratio of total flux. Renders at the official resolution and spp.

  bench/course_exr_compare.py SET [--spp 100] [--pt build/pt]   (e.g. SET = 2022-hw6-directLighting)

Needs the OpenEXR Python module (pip install OpenEXR) and numpy.
"""
import argparse, os, subprocess, tempfile
import numpy as np
import OpenEXR

def read(path):
    with OpenEXR.File(path) as f:
        ch = f.channels()
        if 'RGBA' in ch: rgb = ch['RGBA'].pixels[..., :3]
        elif 'RGB' in ch: rgb = ch['RGB'].pixels
        else: rgb = np.stack([ch[c].pixels for c in 'RGB'], axis=-1)
        return np.asarray(rgb, dtype=np.float64)

def blocks(a, k=16):
    h, w = a.shape[0] // k * k, a.shape[1] // k * k
    return a[:h, :w].reshape(h // k, k, w // k, k, 3).mean(axis=(1, 3))

def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument('set')
    ap.add_argument('--shared', default=os.path.join(here, '..', '..', 'shared', 'ceng795', 'scenes'))
    ap.add_argument('--pt', default=os.path.join(here, '..', 'build', 'pt'))
    ap.add_argument('--spp', type=int, default=100)
    ap.add_argument('--extra', default='', help='more pt options, e.g. "--integrator path"')
    a = ap.parse_args()
    inputs, outputs = os.path.join(a.shared, a.set, 'inputs'), os.path.join(a.shared, a.set, 'outputs')
    out = tempfile.mkdtemp(prefix='pt_exr_')
    print('| image | block mean relative difference | flux pt / official |')
    print('|---|---|---|')
    for xml in sorted(f for f in os.listdir(inputs) if f.endswith('.xml')):
        d = os.path.join(out, xml[:-4])
        subprocess.run([a.pt, 'render', os.path.join(inputs, xml), '--spp', str(a.spp), '-q', '-o', d] + a.extra.split(),
                       check=True, capture_output=True)
        for exr in sorted(f for f in os.listdir(d) if f.endswith('.exr')):
            ref = os.path.join(outputs, exr)
            if not os.path.exists(ref):
                continue
            ours, official = read(os.path.join(d, exr)), read(ref)
            bo, br = blocks(ours), blocks(official)
            rel = np.abs(bo - br).sum() / max(br.sum(), 1e-30)
            print(f'| {exr} | {100 * rel:.2f}% | {ours.sum() / official.sum():.4f} |', flush=True)

if __name__ == '__main__':
    main()
