"""Pictures: :class:`TopDown` (generic map-frame canvas) and the track previews built on it."""

from .topdown import TopDown

__all__ = ["TopDown"]
