"""Draws the Runout filters' and reader's menu icons (the PNGs beside this file, which
the plugin compiles in through RunoutIcons.qrc). PNG, not SVG: Debian's
ParaView 5.11 has no Qt SVG image plugin (libqt5svg5 is not among its
dependencies), so an SVG icon would show as none.

Run by Debian's python3 with python3-pil, only to redraw them:
  /usr/bin/python3 paraview_plugin/RunoutPlugin/icons/draw_icons.py
Each is drawn 4 times larger and shrunk, for smooth edges at 32 x 32.
"""
import os

from PIL import Image, ImageDraw

SIZE = 32
SCALE = 4
SLIDE = (205, 205, 205, 255)     # the particles, as ParaView draws them
BASE = (110, 110, 110, 255)
STRAIN = (220, 40, 30, 255)      # the bands' and the strain's red
PROFILE = (240, 140, 20, 255)    # the profile's orange
LOW = (60, 90, 200, 255)
CHECKED = (40, 150, 60, 255)     # the series reader's check mark


def px(*points):
    """32-pixel coordinates to the large canvas's."""
    return [(x * SCALE, y * SCALE) for x, y in points]


def slide(draw):
    """The slide on its slope: a trapezoid over a base line."""
    draw.polygon(px((3, 26), (29, 26), (24, 12), (9, 12)), fill=SLIDE)
    draw.line(px((1, 27), (31, 27)), fill=BASE, width=2 * SCALE)


def plastic_strain(draw):
    # Particles coloured from unstrained (blue) to strained (red).
    for row, y in enumerate(range(10, 26, 4)):
        for x in range(5 + 2 * (3 - row), 28 - 2 * (3 - row), 4):
            t = min(1.0, abs(x - 16) / 10)
            colour = tuple(int(LOW[i] + t * (STRAIN[i] - LOW[i])) for i in range(3)) + (255,)
            draw.ellipse(px((x - 1.5, y - 1.5), (x + 1.5, y + 1.5)), fill=colour)
    draw.line(px((1, 27), (31, 27)), fill=BASE, width=2 * SCALE)


def shear_bands(draw):
    slide(draw)
    for line in (((8, 13), (14, 26)), ((25, 13), (19, 26))):
        draw.line(px(*line), fill=STRAIN, width=3 * SCALE)


def horsts_and_grabens(draw):
    # A graben dropped between two horsts, as outlines.
    outline = dict(fill=None, outline=STRAIN, width=2 * SCALE)
    draw.polygon(px((3, 26), (12, 26), (10, 11), (5, 11)), **outline)
    draw.polygon(px((12, 26), (20, 26), (23, 17), (10, 17)), **outline)
    draw.polygon(px((20, 26), (29, 26), (27, 11), (22, 11)), **outline)
    draw.line(px((1, 27), (31, 27)), fill=BASE, width=2 * SCALE)


def morphology(draw):
    slide(draw)
    draw.line(px((3, 25), (9, 11), (16, 9), (24, 11), (29, 25)), fill=PROFILE,
              width=3 * SCALE, joint="curve")


def morphology_history(draw):
    # A line chart: the toe and the length rising with time, the thickness falling.
    draw.line(px((4, 4), (4, 28), (30, 28)), fill=BASE, width=2 * SCALE)
    draw.line(px((5, 22), (12, 18), (20, 10), (29, 5)), fill=PROFILE, width=3 * SCALE)
    draw.line(px((5, 25), (12, 23), (20, 18), (29, 15)), fill=STRAIN, width=3 * SCALE)
    draw.line(px((5, 14), (14, 19), (29, 22)), fill=LOW, width=3 * SCALE)


def series_reader(draw):
    # Three frames of a series, the front one checked (against the manifest).
    for k in (2, 1, 0):
        x, y = 4 + 4 * k, 12 - 4 * k
        draw.rectangle(px((x, y), (x + 18, y + 16)), fill=SLIDE, outline=BASE, width=SCALE)
    draw.line(px((8, 20), (12, 25), (28, 9)), fill=CHECKED, width=4 * SCALE, joint="curve")


ICONS = {"PlasticStrain": plastic_strain, "ShearBands": shear_bands,
         "HorstsAndGrabens": horsts_and_grabens, "Morphology": morphology,
         "MorphologyHistory": morphology_history, "SeriesReader": series_reader}


def main():
    folder = os.path.dirname(os.path.abspath(__file__))
    for name, draw_icon in ICONS.items():
        image = Image.new("RGBA", (SIZE * SCALE, SIZE * SCALE), (0, 0, 0, 0))
        draw_icon(ImageDraw.Draw(image))
        image.resize((SIZE, SIZE), Image.LANCZOS).save(
            os.path.join(folder, f"Runout{name}.png"), optimize=True)


if __name__ == "__main__":
    main()
