"""Closed-form form factors (Howell's catalogue) used as independent references."""

from __future__ import annotations

from math import atan, log, pi, sqrt


def parallel_rectangles(a: float, b: float, c: float) -> float:
    """F between directly opposed parallel a x b rectangles at distance c (Howell C-11)."""
    x, y = a / c, b / c
    t1 = log(sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y)))
    t2 = x * sqrt(1 + y * y) * atan(x / sqrt(1 + y * y))
    t3 = y * sqrt(1 + x * x) * atan(y / sqrt(1 + x * x))
    return 2.0 / (pi * x * y) * (t1 + t2 + t3 - x * atan(x) - y * atan(y))


def perpendicular_rectangles(l: float, w: float, h: float) -> float:  # noqa: E741
    """F from a w x l rectangle to an h x l rectangle sharing the edge of length l at
    a right angle (Howell C-14)."""
    W, H = w / l, h / l
    r = sqrt(H * H + W * W)
    a = W * atan(1 / W) + H * atan(1 / H) - r * atan(1 / r)
    q1 = (1 + W * W) * (1 + H * H) / (1 + W * W + H * H)
    q2 = (W * W * (1 + W * W + H * H) / ((1 + W * W) * (W * W + H * H))) ** (W * W)
    q3 = (H * H * (1 + H * H + W * W) / ((1 + H * H) * (H * H + W * W))) ** (H * H)
    return (a + 0.25 * log(q1 * q2 * q3)) / (pi * W)
