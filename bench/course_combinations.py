#!/usr/bin/env python3
"""The seed course's experiment: one HW6 Cornell camera rendered with all eight combinations of
next event estimation, importance (cosine) sampling and Russian roulette at equal time, each
against a high-spp reference made with the same depth limit, so all eight estimate one image.
Writes a labelled contact sheet PNG and prints a Markdown table (spp, M paths/s, relMSE).

  bench/course_combinations.py SCENE.xml [--camera 3] [--seconds 10] [--width 256]
      [--reference-spp 2048] [--max-depth 4] [--rr-start 2] [--out DIR]

Needs python3-pil (Debian) and a built pt. The depth limit applies to every combination
(--max-depth D: the camera ray plus D - 1 bounces; the course's MaxRecursionDepth 3 is D = 4),
so roulette on and off converge to the same answer; roulette starts after --rr-start segments
(default 2, from the first bounce on, so that it acts within the course's short paths).
"""
import argparse, csv, os, subprocess, sys
from PIL import Image, ImageDraw

def render(pt, scene, camera, width, out, extra):
    cmd = [pt, 'render', scene, '--camera', str(camera), '--width', str(width), '--height', str(width), '-q', '-o', out] + extra
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"failed: {' '.join(cmd)}\n{r.stderr}")
    return r.stderr

def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser()
    ap.add_argument('scene')
    ap.add_argument('--pt', default=os.path.join(here, '..', 'build', 'pt'))
    ap.add_argument('--camera', type=int, default=3)
    ap.add_argument('--seconds', type=float, default=10)
    ap.add_argument('--width', type=int, default=256)
    ap.add_argument('--reference-spp', type=int, default=2048)
    ap.add_argument('--max-depth', type=int, default=4)
    ap.add_argument('--rr-start', type=int, default=2, help='roulette after this many segments (2: from the first bounce on)')
    ap.add_argument('--out', default='out/combinations')
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    depth = ['--max-depth', str(a.max_depth), '--rr-start', str(a.rr_start)]
    ref = os.path.join(a.out, 'reference.exr')
    if not os.path.exists(ref):
        render(a.pt, a.scene, a.camera, a.width, ref,
               ['--nee', 'on', '--sampling', 'cosine', '--rr', 'off', '--spp', str(a.reference_spp)] + depth)
    rows = []
    for nee in ('on', 'off'):
        for sampling in ('cosine', 'uniform'):
            for rr in ('on', 'off'):
                label = f"NEE {nee}, {'IS' if sampling == 'cosine' else 'uniform'}, RR {rr}"
                name = f"nee-{nee}_{sampling}_rr-{rr}"
                log = os.path.join(a.out, name + '.csv')
                render(a.pt, a.scene, a.camera, a.width, os.path.join(a.out, name + '.exr'),
                       ['--nee', nee, '--sampling', sampling, '--rr', rr, '--time', str(a.seconds),
                        '--reference', ref, '--error-log', log] + depth)
                spp, seconds, relmse = open(log).read().strip().splitlines()[-1].split(',')
                mpaths = a.width * a.width * int(spp) / float(seconds) / 1e6
                rows.append((label, name, int(spp), float(seconds), mpaths, float(relmse)))
    with open(os.path.join(a.out, 'combinations.csv'), 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['config', 'spp', 'seconds', 'mpaths_per_s', 'relmse'])
        for label, _, spp, seconds, mpaths, relmse in rows:
            w.writerow([label, spp, f'{seconds:.3f}', f'{mpaths:.3f}', f'{relmse:.6f}'])
    # Contact sheet: 4 x 2 tiles, each labelled with its configuration, spp and relMSE.
    tile = a.width
    sheet = Image.new('RGB', (4 * tile, 2 * (tile + 28)), 'white')
    draw = ImageDraw.Draw(sheet)
    for i, (label, name, spp, seconds, mpaths, relmse) in enumerate(rows):
        x, y = (i % 4) * tile, (i // 4) * (tile + 28)
        sheet.paste(Image.open(os.path.join(a.out, name + '.png')).convert('RGB').resize((tile, tile)), (x, y + 28))
        draw.text((x + 4, y + 2), label, fill='black')
        draw.text((x + 4, y + 14), f'{spp} spp, relMSE {relmse:.4f}', fill='black')
    sheet_path = os.path.join(a.out, 'contact_sheet.png')
    sheet.save(sheet_path)
    print(f"Scene {a.scene}, camera {a.camera}, {a.width}x{a.width}, {a.seconds:g} s each, max depth {a.max_depth}; "
          f"roulette from segment {a.rr_start}; reference {a.reference_spp} spp (NEE, IS, no RR). Contact sheet: {sheet_path}\n")
    print('| configuration | spp | M paths/s | relMSE |')
    print('|---|---|---|---|')
    for label, _, spp, seconds, mpaths, relmse in rows:
        print(f'| {label} | {spp} | {mpaths:.3f} | {relmse:.5f} |')

if __name__ == '__main__':
    main()
