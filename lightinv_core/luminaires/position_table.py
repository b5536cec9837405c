"""CIE 117:1995 Table 4.1: the Guth position index p tabulated by H/R and T/R, and its
bilinear interpolation, as CIE 190's UGR tables use it (``ugr_table.py``).

H is the luminaire's height above the line of sight, T its distance sideways from it and
R its distance along it (all from the eye). The table runs over T/R = 0 ... 3 and H/R =
0 ... 1.9 in steps of 0.1; its top cells at small T/R are not defined ("-": no index
there, the luminaire is out of the field). A value between the cells is the bilinear
blend of the four around it, undefined if one of those with a weight is undefined.

The cells are the standard's as eulumdat-ugr 1.0.2 (MIT, the test extra) transcribes
them, with two oddities as published: T/R = 0.1 starts at 1.05 (above T/R = 0's 1.00
and 1.26 to its right's 1.22) and T/R = 2.7, H/R = 0.6 reads 7.50 (its neighbours 7.00
and 7.08). Ten cells are also checked against values published elsewhere
(tests/core/test_ugr.py). ``ugr.guth_index`` is Guth's smooth formula for the same index
(median 4.5% from these cells); observers placed in a room are rated with it.
"""

from __future__ import annotations

import numpy as np

STEP = 0.1
"""The table's step in both T/R and H/R."""

# Rows: T/R (first column); columns: H/R = 0.0 ... 0.9 here, 1.0 ... 1.9 in the next.
_LOW = """
0.0  1.00  1.26  1.53  1.90  2.35  2.86  3.50  4.20  5.00  6.00
0.1  1.05  1.22  1.46  1.80  2.20  2.75  3.40  4.10  4.80  5.80
0.2  1.12  1.30  1.50  1.80  2.20  2.66  3.18  3.88  4.60  5.50
0.3  1.22  1.38  1.60  1.97  2.25  2.70  3.25  3.90  4.60  5.45
0.4  1.32  1.47  1.70  1.96  2.35  2.80  3.30  3.90  4.60  5.40
0.5  1.43  1.60  1.82  2.10  2.48  2.91  3.40  3.98  4.70  5.50
0.6  1.55  1.72  1.98  2.30  2.65  3.10  3.60  4.10  4.80  5.50
0.7  1.70  1.88  2.12  2.48  2.87  3.30  3.78  4.30  4.88  5.60
0.8  1.82  2.00  2.32  2.70  3.08  3.50  3.92  4.50  5.10  5.75
0.9  1.96  2.20  2.54  2.90  3.30  3.70  4.20  4.75  5.30  6.00
1.0  2.11  2.40  2.75  3.10  3.50  3.91  4.40  5.00  5.60  6.20
1.1  2.30  2.55  2.92  3.30  3.72  4.20  4.70  5.25  5.80  6.55
1.2  2.40  2.75  3.12  3.50  3.90  4.35  4.85  5.50  6.05  6.70
1.3  2.55  2.90  3.30  3.70  4.20  4.65  5.20  5.70  6.30  7.00
1.4  2.70  3.10  3.50  3.90  4.35  4.85  5.35  5.85  6.50  7.25
1.5  2.85  3.15  3.65  4.10  4.55  5.00  5.50  6.20  6.80  7.50
1.6  2.95  3.40  3.80  4.25  4.75  5.20  5.75  6.30  7.00  7.65
1.7  3.10  3.55  4.00  4.50  4.90  5.40  5.95  6.50  7.20  7.80
1.8  3.25  3.70  4.20  4.65  5.10  5.60  6.10  6.75  7.40  8.00
1.9  3.43  3.86  4.30  4.75  5.20  5.70  6.30  6.90  7.50  8.17
2.0  3.50  4.00  4.50  4.90  5.35  5.80  6.40  7.10  7.70  8.30
2.1  3.60  4.17  4.65  5.05  5.50  6.00  6.60  7.20  7.82  8.45
2.2  3.75  4.25  4.72  5.20  5.60  6.10  6.70  7.35  8.00  8.55
2.3  3.85  4.35  4.80  5.25  5.70  6.22  6.80  7.40  8.10  8.65
2.4  3.95  4.40  4.90  5.35  5.80  6.30  6.90  7.50  8.20  8.80
2.5  4.00  4.50  4.96  5.40  5.85  6.40  6.95  7.55  8.25  8.85
2.6  4.07  4.55  5.05  5.47  5.95  6.46  7.00  7.65  8.35  8.95
2.7  4.10  4.60  5.10  5.53  6.00  6.50  7.50  7.70  8.40  9.00
2.8  4.15  4.62  5.15  5.56  6.05  6.55  7.08  7.73  8.45  9.05
2.9  4.20  4.65  5.17  5.60  6.07  6.57  7.12  7.75  8.50  9.10
3.0  4.22  4.67  5.20  5.65  6.12  6.60  7.15  7.80  8.55  9.12
"""
_HIGH = """
0.0  7.00  8.10  9.25 10.35 11.70 13.15 14.70 16.20     -     -
0.1  6.80  8.00  9.10 10.30 11.60 13.00 14.60 16.10     -     -
0.2  6.50  7.60  8.75  9.85 11.20 12.70 14.00 15.70     -     -
0.3  6.45  7.40  8.40  9.50 10.85 12.10 13.70 15.00     -     -
0.4  6.40  7.30  8.30  9.40 10.60 11.90 13.20 14.60 16.00     -
0.5  6.40  7.30  8.30  9.40 10.50 11.75 13.00 14.40 15.70     -
0.6  6.40  7.35  8.40  9.40 10.50 11.70 13.00 14.10 15.40     -
0.7  6.50  7.40  8.50  9.50 10.50 11.70 12.85 14.00 15.20     -
0.8  6.60  7.50  8.60  9.50 10.60 11.75 12.80 14.00 15.10     -
0.9  6.75  7.70  8.70  9.65 10.75 11.80 12.90 14.00 15.00 16.00
1.0  7.00  7.90  8.80  9.75 10.80 11.90 12.95 14.00 15.00 16.00
1.1  7.20  8.15  9.00  9.90 10.95 12.00 13.00 14.00 15.00 16.00
1.2  7.50  8.30  9.20 10.00 11.02 12.10 13.10 14.00 15.00 16.00
1.3  7.70  8.55  9.35 10.20 11.20 12.25 13.20 14.00 15.00 16.00
1.4  8.00  8.70  9.50 10.40 11.40 12.40 13.25 14.05 15.00 16.00
1.5  8.20  8.85  9.70 10.55 11.50 12.50 13.30 14.05 15.02 16.00
1.6  8.40  9.00  9.80 10.80 11.75 12.60 13.40 14.20 15.10 16.00
1.7  8.50  9.20 10.00 10.85 11.85 12.75 13.45 14.20 15.10 16.00
1.8  8.65  9.35 10.10 11.00 11.90 12.80 13.50 14.20 15.10 16.00
1.9  8.80  9.50 10.20 11.00 12.00 12.82 13.55 14.20 15.10 16.00
2.0  8.90  9.60 10.40 11.10 12.00 12.85 13.60 14.30 15.10 16.00
2.1  9.00  9.75 10.50 11.20 12.10 12.90 13.70 14.35 15.10 16.00
2.2  9.15  9.85 10.60 11.30 12.10 12.90 13.70 14.40 15.15 16.00
2.3  9.30  9.90 10.70 11.40 12.20 12.95 13.70 14.40 15.20 16.00
2.4  9.40 10.00 10.80 11.50 12.25 13.00 13.75 14.45 15.20 16.00
2.5  9.50 10.05 10.85 11.55 12.30 13.00 13.80 14.50 15.25 16.00
2.6  9.55 10.10 10.90 11.60 12.32 13.00 13.80 14.50 15.25 16.00
2.7  9.60 10.16 10.92 11.63 12.35 13.00 13.80 14.50 15.25 16.00
2.8  9.65 10.20 10.95 11.65 12.35 13.00 13.80 14.50 15.25 16.00
2.9  9.70 10.23 10.95 11.65 12.35 13.00 13.80 14.50 15.25 16.00
3.0  9.70 10.23 10.95 11.65 12.35 13.00 13.80 14.50 15.25 16.00
"""
# "-": not defined (no index above the line of sight that high).


def _parse(text: str) -> np.ndarray:
    rows = [line.split() for line in text.strip().splitlines()]
    return np.array([[np.nan if v == "-" else float(v) for v in r[1:]] for r in rows])


TABLE = np.hstack([_parse(_LOW), _parse(_HIGH)])
"""p by (T/R row, H/R column), shape (31, 20); nan where the table defines none."""
TR_AXIS = np.arange(TABLE.shape[0]) * STEP
"""T/R of the rows: 0.0 ... 3.0."""
HR_AXIS = np.arange(TABLE.shape[1]) * STEP
"""H/R of the columns: 0.0 ... 1.9."""


def table_position_index(h_over_r, t_over_r) -> np.ndarray:
    """CIE 117 Table 4.1's position index at H/R and T/R (absolute values; broadcast like
    numpy), interpolated bilinearly; nan outside the table or its defined cells."""
    h = np.abs(np.asarray(h_over_r, dtype=float))
    t = np.abs(np.asarray(t_over_r, dtype=float))
    h, t = np.broadcast_arrays(h, t)
    inside = (t <= TR_AXIS[-1] + 1e-9) & (h <= HR_AXIS[-1] + 1e-9)
    # The cell below and left of each point, and where in it the point lies (0 ... 1).
    i = np.clip(np.floor(t / STEP + 1e-9).astype(int), 0, len(TR_AXIS) - 2)
    j = np.clip(np.floor(h / STEP + 1e-9).astype(int), 0, len(HR_AXIS) - 2)
    ft = np.clip(t / STEP - i, 0.0, 1.0)
    fh = np.clip(h / STEP - j, 0.0, 1.0)
    total = np.zeros(h.shape)
    defined = inside.copy()
    for di, dj, w in (
        (0, 0, (1 - ft) * (1 - fh)),
        (1, 0, ft * (1 - fh)),
        (0, 1, (1 - ft) * fh),
        (1, 1, ft * fh),
    ):
        v = TABLE[i + di, j + dj]
        # A corner with no weight (a point on a cell's edge) may be undefined.
        used = w > 1e-12
        defined &= ~(used & np.isnan(v))
        total += np.where(used, w * np.nan_to_num(v), 0.0)
    return np.where(defined, total, np.nan)
