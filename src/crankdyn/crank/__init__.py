"""One cylinder's mechanism: the slider-crank geometry, its kinematics, the equivalent masses,
the cylinder pressure (measured traces and the Wiebe model) and indicated quantities."""
