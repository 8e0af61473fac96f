"""Plane geometry: a spec's walls, joins and openings as boxes (:mod:`.building`, over :mod:`.runs`, :mod:`.joins`,
:mod:`.openings` and :mod:`.vectors`) and its tape lines as boxes and discs (:mod:`.tape`), on the build path: no
shapely; and a scene's rooms, gaps and free floor (:mod:`.enclosure`, :mod:`.placement`, with shapely) and its
floor markings (:mod:`.markings`)."""
