"""Figures, the quick-look plots, the index page: everything drawn from datasets and histories.

Nothing is imported here.
"""
