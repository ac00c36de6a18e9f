"""From an occupancy map to a corridor: the first steps of the data flow.

* :mod:`.occupancy` -- the ROS occupancy map (``load_map``, ``OccupancyMap``, ``save_map``);
* :mod:`.corridor` -- the drivable corridor of a map: walls and a centreline;
* :mod:`.direction` -- the corridor's racing direction;
* :mod:`.gaps` -- closing small gaps in a map's walls before the corridor is extracted;
* :mod:`.clearance_path` -- the path of most clearance through an open map;
* :mod:`.car_fit` -- whether, and where, the car's footprint fits the corridor.

The result of the flow is a :class:`~roboracer_arena.track.drivable.Track`.
"""
