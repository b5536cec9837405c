"""Sources: the kinds of source (their types and registry) and the zone emission of
rectangular sources.
"""
