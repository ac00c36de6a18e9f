"""Pictures: top-down drawings of maps, tracks and simulated episodes, and video writers."""
