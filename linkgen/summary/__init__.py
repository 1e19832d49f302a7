"""The engineering summary: mobility, four-bar loops and their Grashof class, the input range
that assembles, limit positions and change points, transmission angles, strokes, swings and
time ratios, and the rows that fail, all in the file's units: found by ``compute.summarize``
(it evaluates the procedure), held as plain records (``records``: the step log carries them)
and written as text, Markdown or JSON (``text``, which reads the records only)."""
