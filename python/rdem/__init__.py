"""rdem from Python: a DEM simulator for granular materials that runs LIGGGHTS 3.8 scripts.

    import rdem
    sim = rdem.Simulation(threads=2)
    sim.file("in.pour")            # any LIGGGHTS script, as `rdem -in in.pour`
    sim.command("run 1000")
    x = sim.x                      # positions: a numpy copy (n x 3), rows in storage order
    ids = sim.tag                  # which particle each row is
    ke = sim.thermo["ke"]          # the thermo column of the last run

Arrays: the attributes (``sim.x``, ``v``, ``omega``, ``f``, ``torque``, ``radius``,
``mass``, ``tag``, ``type``) and ``sim.array(name)`` (named per-particle properties too)
are copies: writing to them never changes the simulation. ``sim.view(name)`` gives a
read-only view of rdem's own storage, without a copy; no command runs while a view is
alive (delete it first), because a command may move that storage.

Errors of a command raise :class:`RdemError` with ``file``, ``line``, ``column``,
``message`` and the rendered ``report``; the simulation stays usable. The GIL is
released while commands run; Ctrl-C ends a run after the current step and raises
KeyboardInterrupt, and the next ``run`` continues from there.
"""

from ._rdem import RdemError, Simulation, StepView, __version__

__all__ = ["Simulation", "StepView", "RdemError", "__version__"]
