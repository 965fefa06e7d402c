#!/usr/bin/env python3
"""Renders side by side in one JPEG, each captioned, at one exposure: what an equal-time table
looks like. Images larger than the first (an official reference at full size) are box-filtered
down to its size by a whole factor, as `pt render --reference` does.

  /opt/mitsuba/bin/python bench/side_by_side.py OUT.jpg A.exr "caption A" B.exr "caption B" ...
      [--exposure STOPS]

The exposure defaults to the one that puts the first image's mean at 0.18 (sRGB-encoded, clipped).
Needs the OpenEXR Python module, numpy and PIL.
"""
import argparse

import numpy as np
import OpenEXR
from PIL import Image, ImageDraw


def read_rgb(path):
    with OpenEXR.File(path) as f:
        channels = f.channels()
        if "RGBA" in channels:
            rgb = channels["RGBA"].pixels[..., :3]
        elif "RGB" in channels:
            rgb = channels["RGB"].pixels
        else:
            rgb = np.stack([channels[c].pixels for c in "RGB"], axis=-1)
        return np.asarray(rgb, dtype=np.float64)


def box_filter_to(rgb, height, width):
    fy, fx = rgb.shape[0] // height, rgb.shape[1] // width
    if fy * height != rgb.shape[0] or fx * width != rgb.shape[1] or fx != fy:
        raise SystemExit(f"cannot box-filter {rgb.shape[1]}x{rgb.shape[0]} to {width}x{height}")
    return rgb.reshape(height, fy, width, fx, 3).mean(axis=(1, 3))


def srgb(linear):
    linear = np.clip(linear, 0.0, 1.0)
    return np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.power(linear, 1 / 2.4) - 0.055)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("pairs", nargs="+", help="EXR caption EXR caption ...")
    parser.add_argument("--exposure", type=float)
    args = parser.parse_args()
    if len(args.pairs) % 2:
        raise SystemExit("give each image a caption")
    images = [read_rgb(p) for p in args.pairs[0::2]]
    captions = args.pairs[1::2]
    height, width = images[0].shape[:2]
    images = [im if im.shape[:2] == (height, width) else box_filter_to(im, height, width) for im in images]
    scale = 2.0**args.exposure if args.exposure is not None else 0.18 / max(images[0].mean(), 1e-12)
    caption_height = 18
    sheet = Image.new("RGB", (width * len(images), height + caption_height), "white")
    draw = ImageDraw.Draw(sheet)
    for i, (im, caption) in enumerate(zip(images, captions)):
        pixels = (srgb(im * scale) * 255 + 0.5).astype(np.uint8)
        sheet.paste(Image.fromarray(pixels), (i * width, caption_height))
        draw.text((i * width + 4, 3), caption, fill="black")
    sheet.save(args.out, quality=90)


if __name__ == "__main__":
    main()
