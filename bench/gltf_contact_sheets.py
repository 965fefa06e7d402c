#!/usr/bin/env python3
"""Contact sheets of Khronos glTF sample models: pt's render beside the model's upstream
screenshot (the Khronos sample viewer's look: a visual check, not a reference image).

Each model is rendered under a studio environment made here (a dim grey gradient with two
softboxes and a top light, so coats and sheens have something to reflect), at the framing camera
`pt render` gives a scene without one (at the screenshot's aspect), and placed left of screenshot/screenshot.jpg (or .png) scaled to the
same height; the sheet's caption says the model, the spp, the seconds and any loader warning.

  /usr/bin/python3 bench/gltf_contact_sheets.py [--model-dir DIR] [--pt build/pt] [--spp 256]
      [--size 360] [--out bench/images] [MODEL ...]
  (default models: ClearCoatTest SheenCloth IridescenceSuzanne AnisotropyStrengthTest, from
   ../shared/gltf-samples; needs python3-numpy, python3-pil)
"""
import argparse
import pathlib
import struct
import subprocess
import sys
import tempfile

import numpy as np
from PIL import Image, ImageDraw

ROOT = pathlib.Path(__file__).resolve().parent.parent


def write_exr(path, rgb):
    """An uncompressed scanline OpenEXR file of float32 R, G, B (rows top to bottom)."""
    height, width, _ = rgb.shape

    def attribute(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value

    channels = b"".join(c.encode() + b"\0" + struct.pack("<iBBBBii", 2, 0, 0, 0, 0, 1, 1) for c in "BGR") + b"\0"
    window = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (struct.pack("<ii", 20000630, 2) + attribute("channels", "chlist", channels) +
              attribute("compression", "compression", b"\0") + attribute("dataWindow", "box2i", window) +
              attribute("displayWindow", "box2i", window) + attribute("lineOrder", "lineOrder", b"\0") +
              attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              attribute("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    line_bytes = 3 * 4 * width
    first = len(header) + 8 * height
    offsets = b"".join(struct.pack("<Q", first + y * (8 + line_bytes)) for y in range(height))
    lines = []
    for y in range(height):
        row = rgb[y].astype("<f4")
        data = row[:, 2].tobytes() + row[:, 1].tobytes() + row[:, 0].tobytes()
        lines.append(struct.pack("<ii", y, line_bytes) + data)
    pathlib.Path(path).write_bytes(header + offsets + b"".join(lines))


def studio_environment(width=512, height=256):
    """Equirectangular radiance: a grey gradient, two warm-white softboxes, a top light."""
    v = (np.arange(height) + 0.5) / height  # 0 at the top (+y)
    u = (np.arange(width) + 0.5) / width
    elevation = (0.5 - v)[:, None] * np.pi  # +pi/2 up
    azimuth = (u[None, :] - 0.5) * 2 * np.pi
    sky = 0.45 + 0.55 * np.clip(np.sin(elevation), 0, 1)
    rgb = np.repeat(np.broadcast_to(sky, (height, width))[..., None], 3, axis=2).copy()
    rgb[elevation[:, 0] < 0] *= 0.5  # a darker floor

    def box(az, el, half_az, half_el, radiance):
        inside = (np.abs(azimuth - az) < half_az) & (np.abs(elevation - el) < half_el)
        rgb[inside] = radiance

    box(-0.9, 0.35, 0.25, 0.3, (12.0, 11.5, 10.5))
    box(1.3, 0.2, 0.15, 0.35, (7.0, 7.3, 7.8))
    rgb[elevation[:, 0] > 1.3] = (5.0, 5.0, 5.0)
    return rgb


def caption_bar(width, lines):
    bar = Image.new("RGB", (width, 6 + 14 * len(lines)), (255, 255, 255))
    draw = ImageDraw.Draw(bar)
    for i, line in enumerate(lines):
        draw.text((6, 4 + 14 * i), line, fill=(0, 0, 0))
    return bar


def sheet(model_dir, model, args, work):
    gltf = model_dir / model / "glTF" / f"{model}.gltf"
    out_exr = work / f"{model}.exr"
    shots = sorted((model_dir / model / "screenshot").glob("screenshot.*"))
    if not shots:
        sys.exit(f"{model}: no screenshot/screenshot.* in {model_dir / model}")
    shot = Image.open(shots[0]).convert("RGB")
    width = max(1, round(args.size * shot.width / shot.height))  # the screenshot's aspect
    cmd = [str(args.pt), "render", str(gltf), "--env", str(work / "studio.exr"), "--spp", str(args.spp),
           "--width", str(width), "--height", str(args.size), "-o", str(out_exr)]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{model}: pt failed:\n{run.stderr}")
    warnings = [line for line in run.stderr.splitlines() if "warning" in line or "not supported" in line]
    summary = next((line for line in run.stderr.splitlines() if "wrote" in line), "")
    seconds = summary.split(" spp in ")[1].split(" s,")[0] if " spp in " in summary else "?"
    ours = Image.open(work / f"{model}.png").convert("RGB")
    shot = shot.resize((max(1, round(shot.width * ours.height / shot.height)), ours.height), Image.LANCZOS)
    body = Image.new("RGB", (ours.width + shot.width + 8, ours.height), (255, 255, 255))
    body.paste(ours, (0, 0))
    body.paste(shot, (ours.width + 8, 0))
    text = f"{model}: pt, {args.spp} spp in {seconds} s, " + (f"{len(warnings)} warning(s)" if warnings else "no warnings")
    bar = caption_bar(body.width, [text, "left: pt (studio environment); right: Khronos sample viewer screenshot"])
    full = Image.new("RGB", (body.width, body.height + bar.height), (255, 255, 255))
    full.paste(bar, (0, 0))
    full.paste(body, (0, bar.height))
    target = args.out / f"gltf_{model}_contact.jpg"
    full.save(target, quality=90)
    print(f"{target}: {text}")
    for w in warnings:
        print(f"  {w}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("models", nargs="*",
                        default=["ClearCoatTest", "SheenCloth", "IridescenceSuzanne", "AnisotropyStrengthTest"])
    parser.add_argument("--model-dir", type=pathlib.Path, default=ROOT.parent / "shared" / "gltf-samples")
    parser.add_argument("--pt", type=pathlib.Path, default=ROOT / "build" / "pt")
    parser.add_argument("--spp", type=int, default=256)
    parser.add_argument("--size", type=int, default=360)
    parser.add_argument("--out", type=pathlib.Path, default=ROOT / "bench" / "images")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        write_exr(work / "studio.exr", studio_environment())
        for model in args.models:
            sheet(args.model_dir, model, args, work)


if __name__ == "__main__":
    main()
