"""What every floor above stands on, knowing nothing of maps or tracks.

* :mod:`.fileio` -- bounded reads and atomic writes at the edges;
* :mod:`.strict` -- strict pydantic models (numbers are numbers) and one-line validation errors;
* :mod:`.frozen_model` -- the frozen strict model base;
* :mod:`.paths` -- where the package finds its data;
* :mod:`.worker_pool` -- the package's one pool of worker processes.
"""
