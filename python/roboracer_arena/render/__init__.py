"""Pictures: :class:`TopDown` (generic map-frame canvas), the track previews built on it,
top-down drawings of simulated episodes, and video writers."""

from .topdown import TopDown

__all__ = ["TopDown"]
