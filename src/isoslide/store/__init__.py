"""The data store: time histories and their tables, provenance, progress of long runs.

Nothing is imported here.
"""
