"""Pictures: :class:`TopDown` (generic map-frame canvas with collision-free labels), the
track previews built on it (:mod:`.preview`, framed by :mod:`.frame`, race markings from
:mod:`.race_marks`), the offscreen 3D still of a stage (:mod:`.still3d`, ``render3d``
extra), top-down drawings of simulated episodes (:mod:`.sim_view`), video writers
(:mod:`.video`) and the output formats all of them accept (:mod:`.formats`)."""

from .topdown import TopDown

__all__ = ["TopDown"]
