"""Pipelines, reports and the ``gearloss`` command line that combine the three stages."""
