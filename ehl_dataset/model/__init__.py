"""Micro-scale building blocks of the homogenised (two-scale, averaged-Reynolds) mixed-EHL model."""
