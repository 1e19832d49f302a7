"""Instant centres (issue 21): every pair of links' centre, named as an output (``names``),
classified from the topology (``classify``), computed by an ``instant_centre`` step per centre
(``steps``; the primitive is linkgen/primitives/centres.py), kept at the sketch in the step log
(``record``), tabled (``table``) and drawn (``figure``)."""
