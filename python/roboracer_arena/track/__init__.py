"""The drivable track, the end of the map -> corridor -> direction flow.

* :mod:`.drivable` -- :class:`~.drivable.Track` (walls and a closed centreline in its
  racing direction) and the track of a ROS map file;
* :mod:`.start_grid` -- where the cars of a track start.
"""
