"""Silhouettes in raster images (scikit-image and imageio, extra ``image``)."""

from __future__ import annotations

import io
import re
from typing import Any

import numpy as np

from ..model.outline import fill_rings
from ._drawing import Drawing, Shape, TolOf
from .limits import MAX_PIXELS, LimitExceeded

#: Blobs smaller than this fraction of the largest one (or than 9 pixels) are noise.
MIN_BLOB = 1e-3
#: An alpha channel is the silhouette when at least this fraction of the image is
#: transparent (a few clear corner pixels of an opaque picture are not a background).
MIN_TRANSPARENT = 0.01


def approximate_chain(coords: np.ndarray, tolerance: float) -> np.ndarray:
    """The Douglas-Peucker approximation of the chain ``coords`` (K, 2) within
    ``tolerance``: scikit-image's ``measure.approximate_polygon``, the same arithmetic
    in the same order (so the same points), without importing ``scipy.signal`` as its
    module does (0.6 s of a fresh process reading an image).  A point beside a segment
    is at its perpendicular distance, one beyond either end at its distance from the
    nearer end; each segment is split at its farthest point while that is beyond the
    tolerance.  ``tolerance <= 0``: ``coords`` itself."""
    if tolerance <= 0:
        return coords
    chain = np.zeros(coords.shape[0], bool)
    dists = np.zeros(coords.shape[0])
    chain[0] = chain[-1] = True
    stack = [(0, coords.shape[0] - 1)]
    while stack:
        start, end = stack.pop()
        r0, c0 = coords[start, :]
        r1, c1 = coords[end, :]
        dr, dc = r1 - r0, c1 - c0
        angle = -np.arctan2(dr, dc)
        offset = c0 * np.sin(angle) + r0 * np.cos(angle)
        inner = coords[start + 1:end, :]
        d = dists[start + 1:end]
        dr0, dc0 = inner[:, 0] - r0, inner[:, 1] - c0
        dr1, dc1 = inner[:, 0] - r1, inner[:, 1] - c1
        perp = (dr0 * dr + dc0 * dc > 0) & (-dr1 * dr - dc1 * dc > 0)
        ends = ~perp
        d[perp] = np.abs(inner[perp, 0] * np.cos(angle) + inner[perp, 1] * np.sin(angle)
                         - offset)
        d[ends] = np.minimum(np.sqrt(dc0[ends] ** 2 + dr0[ends] ** 2),
                             np.sqrt(dc1[ends] ** 2 + dr1[ends] ** 2))
        if np.any(d > tolerance):
            split = start + int(np.argmax(d)) + 1
            stack.append((split, end))
            stack.append((start, split))
            chain[split] = True
    out: np.ndarray = coords[chain, :]
    return out


def _gray(img: np.ndarray) -> np.ndarray:
    from skimage import color

    img = np.asarray(img)
    if img.ndim == 3 and img.shape[2] in (2, 4):
        alpha = img[..., -1].astype(float)
        clear = alpha < 0.5 * float(alpha.max())
        if clear.mean() >= MIN_TRANSPARENT:    # a transparent background: alpha is the part
            return 1.0 - alpha / max(float(alpha.max()), 1.0)
        img = img[..., :-1]
    if img.ndim == 3 and img.shape[2] == 3:
        img = color.rgb2gray(img)
    elif img.ndim == 3 and img.shape[2] == 1:
        img = img[..., 0]
    img = img.astype(float)
    hi = float(img.max()) if img.size else 0.0
    return img / hi if hi > 0 else img


def read_image(data: bytes, tol_of: TolOf, threshold: float | None = None) -> Drawing:
    """Blobs of a silhouette image, in pixels with y down.

    The image is made grey (an alpha channel with contrast is the silhouette), split at
    ``threshold`` (a grey level in [0, 1]; default Otsu's), and the class that covers most
    of the image's border is the background: a band of background touching the border is
    never taken for the part.  Blobs of the other class that touch the border are left out
    when others do not.  Each blob is traced with its holes (``find_contours``) and
    simplified to ``tol_of`` pixels (``approximate_polygon``)."""
    try:
        import imageio.v3 as iio
        from skimage import filters, measure, segmentation
    except ImportError as exc:  # pragma: no cover - depends on the install
        raise ValueError("reading images needs scikit-image: pip install "
                         "'fcgrasp[image]'") from exc
    try:
        from PIL import Image

        with Image.open(io.BytesIO(data)) as probe:      # the header only: no decoding
            w, h = probe.size
    except Exception as exc:  # pillow raises several kinds on broken headers
        # (pillow's "cannot identify image file <_io.BytesIO object at 0x...>" names an
        # address that changes from run to run)
        why = re.sub(r"\s*<[^>]*object at 0x[0-9a-f]+>", "", str(exc).splitlines()[0])
        raise ValueError(f"not a readable image ({why[:120]})") from exc
    if w * h > MAX_PIXELS:
        raise LimitExceeded(f"the image's pixels: {w} x {h}, more than {MAX_PIXELS:,} "
                            f"(a fixed limit)")
    try:
        img: Any = iio.imread(io.BytesIO(data), index=0, plugin="pillow")
    except Exception as exc:  # imageio raises several kinds
        raise ValueError(f"not a readable image ({str(exc).splitlines()[0][:120]})") from exc
    g = _gray(img)
    if g.ndim != 2 or min(g.shape) < 3 or np.ptp(g) == 0:
        raise ValueError("the image has no contrast, no silhouette to trace")
    thr = filters.threshold_otsu(g) if threshold is None else threshold
    dark = g < thr
    if dark.all() or not dark.any():
        raise ValueError(f"threshold {thr:.3g} leaves the whole image on one side: no "
                         f"silhouette")
    border = np.concatenate([dark[0], dark[-1], dark[:, 0], dark[:, -1]])
    mask = dark if border.mean() < 0.5 else ~dark        # the part is not the border's class
    labels = measure.label(mask, connectivity=2)
    inner = segmentation.clear_border(labels)
    notes = []
    if inner.max() > 0:
        if (labels > 0).sum() > (inner > 0).sum():
            notes.append("blobs touching the image border were left out")
        labels = inner
    else:
        notes.append("every blob touches the image border")
    props = measure.regionprops(labels)
    if not props:
        raise ValueError("no silhouette found")
    biggest = max(p.area for p in props)
    tol = tol_of(float(max(g.shape)), "px")
    shapes: list[Shape] = []
    for p in sorted(props, key=lambda p: p.label):
        if p.area < max(9, MIN_BLOB * biggest):
            continue
        r0, c0, r1, c1 = p.bbox
        blob = np.pad(labels[r0:r1, c0:c1] == p.label, 1).astype(float)
        rings = []
        for c in measure.find_contours(blob, 0.5):
            c = approximate_chain(c, tol)
            rings.append(np.column_stack([c[:, 1] + c0 - 1, c[:, 0] + r0 - 1]))
        for j, poly in enumerate(fill_rings(rings, "evenodd")):
            bid = f"blob{p.label}" + ("" if j == 0 else f"#{j + 1}")
            shapes.append(Shape(poly, bid, (bid,), flatten=tol))
    if not shapes:
        raise ValueError("no silhouette found")
    return Drawing(shapes, "px", "pixels (no physical size: give pixel_size / "
                   "--pixel-size)", y_down=True, notes=notes,
                   height=float(g.shape[0]))
