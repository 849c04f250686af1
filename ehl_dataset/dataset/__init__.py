"""Factorials of contact conditions, the resumable HDF5 store and the runner that computes a factorial into it
(local processes or Dask)."""
