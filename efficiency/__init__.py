"""Stage 3 of gearloss: helical gear pair geometry, kinematics, load distribution, TE, stresses and power loss."""
