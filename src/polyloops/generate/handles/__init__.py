"""The ``handles`` generator (genus 2): the maps of genus 2 that carry a polycube, by the torus
search with the surface's genus a parameter (:mod:`polyloops.generate.torus`).

Both stages carry over (``docs/searches.md``, "Genus 2"): the two-stage theorem and the region
search never used the genus, and the first stage's states become maps whose non-disc faces are
grouped into *pieces*, each of some genus with some boundaries
(:func:`~polyloops.generate.torus.arrangement.piece_mark`); a new curve's arc through a piece is
fixed, up to a homeomorphism of the piece that keeps its boundary, by what cutting along it
leaves.  A map of genus 2 with ``N`` corners has ``N + 2`` crossings, so ``B`` has at most
``(N + 2) / 3``.

>>> from polyloops.generate.base import generators
>>> generators()["handles"].genus, generators()["handles"].crossings(48)
(2, 50)
"""

from __future__ import annotations

from polyloops.generate.base import register
from polyloops.generate.torus import TorusGenerator


class HandlesGenerator(TorusGenerator):
    """The maps of genus 2 that carry a polycube (:class:`~polyloops.generate.torus.TorusGenerator`
    with ``genus = 2``: the same jobs, shares, spilled first stage and options)."""

    name = "handles"
    genus = 2


register(HandlesGenerator())
