"""Instant centres (issue 21): every pair of links' centre, classified from the topology
(``classify``), computed by an ``instant_centre`` step per centre (``steps``, the primitive in
linkgen/primitives/centres.py), tabled (``table``) and drawn (``figure``)."""
