"""The configurations a user writes, each a strict pydantic model.

* :mod:`.build` -- :class:`~.build.BuildConfig`: map to USD stage and physics geometry;
* :mod:`.sim` -- :class:`~.sim.SimConfig`: the simulator's physics, vehicle and lidar;
* :mod:`.constructor` -- :class:`~.constructor.ConstructorConfig`: the track generator's search;
* :mod:`.vehicle_presets` -- named vehicles for :class:`~.sim.VehicleConfig`.
"""
