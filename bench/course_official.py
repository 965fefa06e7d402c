#!/usr/bin/env python3
"""Renders the CENG795 course scenes (../shared/ceng795/scenes) at reduced resolution and
compares each image with the course's official render, as displayed 8-bit images.

For every camera it prints the mean absolute difference of 8x8 block means (0..255 scale,
so noise averages out and what remains is bias) and of single pixels. Needs python3-pil and
python3-numpy (Debian) and a built pt.

  bench/course_official.py [--pt build/pt] [--width 200] [--spp 64] [--sets 2022-hw4-textures,...]
"""
import argparse, os, subprocess, sys, tempfile, time
import numpy as np
from PIL import Image

def block_means(a, k=8):
    h, w = a.shape[0] // k * k, a.shape[1] // k * k
    return a[:h, :w].reshape(h // k, k, w // k, k, 3).mean(axis=(1, 3))

def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument('--pt', default=os.path.join(here, '..', 'build', 'pt'))
    ap.add_argument('--shared', default=os.path.join(here, '..', '..', 'shared', 'ceng795', 'scenes'))
    ap.add_argument('--width', type=int, default=200)
    ap.add_argument('--spp', type=int, default=64)
    ap.add_argument('--sets', default='')
    ap.add_argument('--out', default=tempfile.mkdtemp(prefix='pt_course_'))
    args = ap.parse_args()
    sets = args.sets.split(',') if args.sets else sorted(os.listdir(args.shared))
    print(f'| set | image | integrator | block diff | pixel diff | mean pt / official | seconds |')
    print(f'|---|---|---|---|---|---|---|')
    for s in sets:
        inputs = os.path.join(args.shared, s, 'inputs')
        for xml in sorted(f for f in os.listdir(inputs) if f.endswith('.xml')):
            out = os.path.join(args.out, s, xml[:-4])
            os.makedirs(out, exist_ok=True)
            t0 = time.time()
            r = subprocess.run([args.pt, 'render', os.path.join(inputs, xml), '--width', str(args.width),
                                '--spp', str(args.spp), '-q', '-o', out], capture_output=True, text=True)
            seconds = time.time() - t0
            if r.returncode != 0:
                print(f'| {s} | {xml} | - | error: {r.stderr.strip().splitlines()[-1][:80]} | | | |')
                continue
            integrator = 'classic' if '<Renderer>' not in open(os.path.join(inputs, xml), errors='replace').read() else 'path'
            for png in sorted(f for f in os.listdir(out) if f.endswith('.png')):
                official = os.path.join(args.shared, s, 'outputs', png)
                if not os.path.exists(official):
                    print(f'| {s} | {png} | {integrator} | no official image | | | {seconds:.1f} |')
                    continue
                a = np.asarray(Image.open(os.path.join(out, png)).convert('RGB')).astype(float)
                b = Image.open(official).convert('RGB').resize((a.shape[1], a.shape[0]), Image.BOX)
                b = np.asarray(b).astype(float)
                block = np.abs(block_means(a) - block_means(b)).mean()
                pixel = np.abs(a - b).mean()
                print(f'| {s} | {png} | {integrator} | {block:.2f} | {pixel:.2f} | {a.mean():.1f} / {b.mean():.1f} | {seconds:.1f} |')
            sys.stdout.flush()

if __name__ == '__main__':
    main()
