"""What the window draws: the 3D viewport and its overlays, the daylight maps, the plots.

Every plot is pyqtgraph's, drawn black on white without antialiasing (set here, once,
before any plot is made: pyqtgraph reads it when a plot is created).
"""

import pyqtgraph as pg

pg.setConfigOptions(antialias=False, background="w", foreground="k")
