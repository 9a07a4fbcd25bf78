"""Motion planners behind :func:`cncc.passes.plan.plan_commands`, one module per concern.

* ``limits``     machine limits as arrays
* ``geometry``   commands -> runs between stops; arcs -> chords
* ``segments``   straight segments with caps; junction deviation, speed step
* ``blending``   corner rounding and the velocity-step rule (-O2, -O3)
* ``profile``    TOPP by min-plus scans; trapezoids
* ``fir``        -O2 jerk filter on the path coordinate
* ``windows``    -O2 segment pieces re-timed by ruckig; vertex-state search
* ``onedim``     single moves and independent axes (ruckig, trapezoid, nominal)
* ``optimal``    -O3 windows with CasADi
* ``emit``       path phases -> Trajectory rows
"""
