"""Solvers of the line contact: the damped Newton solver, the steady smooth solve, the homogenised (film-law and
flow-factor) and the deterministic mixed models, the time average of a rough run, the named accuracy levels, the
effect planner and the result record.

The public entry is :func:`ehl_dataset.solver.solve_contact`, which chooses among them.
"""
